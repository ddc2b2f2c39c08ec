// The simplifier's seam groups (src/simplify/seam_groups.*): twins, partners and locks from
// position_vertex, the welded link condition, and position_vertex on output.
#include <catch2/catch.hpp>

#include <vector>

#include "cli/synthetic.h"
#include "simplify/seam_groups.h"
#include "simplify/triangle_fans.h"

using namespace meshsal;
using detail::SeamGroups;
using detail::TriangleFans;

namespace {

// make_plane(2, 4) ([-1, 1]^2) cut along x = 0: the triangles right of the cut get twins
// of its five vertices (ids 25..29, bottom to top).
Mesh cut_plane() {
  Mesh m = make_plane(2.0, 4);
  const size_t nv = m.vertex_count();
  m.position_vertex.resize(nv);
  for (size_t v = 0; v < nv; ++v) m.position_vertex[v] = uint32_t(v);
  std::vector<uint32_t> twin(nv, UINT32_MAX);
  for (size_t t = 0; t < m.triangle_count(); ++t) {
    float cx = 0;
    for (int k = 0; k < 3; ++k) cx += m.positions[3 * m.triangles[3 * t + k]];
    if (cx <= 0) continue;
    for (int k = 0; k < 3; ++k) {
      uint32_t& v = m.triangles[3 * t + k];
      if (m.positions[3 * v] != 0.f) continue;
      if (twin[v] == UINT32_MAX) {
        twin[v] = uint32_t(m.vertex_count());
        m.positions.insert(m.positions.end(), {m.positions[3 * v], m.positions[3 * v + 1], m.positions[3 * v + 2]});
        m.position_vertex.push_back(v);
      }
      v = twin[v];
    }
  }
  return m;
}

std::vector<uint32_t> identity(size_t n) {
  std::vector<uint32_t> v(n);
  for (size_t i = 0; i < n; ++i) v[i] = uint32_t(i);
  return v;
}

uint32_t at(const Mesh& m, float x, float y) {  // the first vertex at (x, y)
  for (uint32_t v = 0; v < m.vertex_count(); ++v)
    if (m.positions[3 * v] == x && m.positions[3 * v + 1] == y) return v;
  return UINT32_MAX;
}

}  // namespace

TEST_CASE("seam groups: twins, partners, locks and the seam's neighbours", "[simplify]") {
  const Mesh m = cut_plane();
  REQUIRE(m.vertex_count() == 30);
  SeamGroups g;
  std::vector<uint8_t> locked(30, 0);
  g.build(m.position_vertex, identity(30), m.triangles, false, &locked);
  CHECK(g.has_twins);
  for (uint32_t v = 0; v < 30; ++v) {
    const bool twin = m.positions[3 * v] == 0.f;
    INFO("vertex " << v);
    CHECK(bool(locked[v]) == twin);
    CHECK(g.pair(v) == twin);
    if (twin) {
      CHECK(g.partner[g.partner[v]] == v);
      CHECK(g.group_of[v] == g.group_of[g.partner[v]]);
      CHECK(g.twin_next[g.twin_next[v]] == v);
      CHECK(g.near_seam[v]);
    } else {
      CHECK(g.group_of[v] == v);
      CHECK(g.twin_next[v] == SeamGroups::NONE);
      CHECK(bool(g.near_seam[v]) == (std::abs(m.positions[3 * v]) == 0.5f));  // one column off
    }
  }
  CHECK(g.seam_edge(at(m, 0, 0), at(m, 0, 0.5f)));
  CHECK_FALSE(g.seam_edge(at(m, 0, 0), at(m, -0.5f, 0)));
  // Locked borders: twins stay locked, but nothing collapses along the seam.
  SeamGroups locked_groups;
  std::vector<uint8_t> locked2(30, 0);
  locked_groups.build(m.position_vertex, identity(30), m.triangles, true, &locked2);
  CHECK(locked2 == locked);
  CHECK_FALSE(locked_groups.pair(at(m, 0, 0)));
}

TEST_CASE("seam groups: a bad position_vertex is an error", "[simplify]") {
  SeamGroups g;
  std::vector<uint8_t> locked(3, 0);
  CHECK_THROWS_AS(g.build({0, 2, 2}, identity(3), {0, 1, 2}, false, &locked), Error);  // points up
  CHECK_THROWS_AS(g.build({0, 0, 1}, identity(3), {0, 1, 2}, false, &locked), Error);  // not a root
  CHECK_THROWS_AS(g.build({0, 1}, identity(3), {0, 1, 2}, false, &locked), Error);     // too short
}

TEST_CASE("seam groups: the welded link condition", "[simplify]") {
  const Mesh m = cut_plane();
  SeamGroups g;
  std::vector<uint8_t> locked(30, 0);
  g.build(m.position_vertex, identity(30), m.triangles, false, &locked);
  TriangleFans f;
  f.corners = m.triangles;
  f.build(30);
  const uint32_t s = at(m, 0, 0), s_up = at(m, 0, 0.5f), left = at(m, -0.5f, 0);
  const uint32_t twin_s = g.partner[s], right = at(m, 0.5f, 0);
  // Welded, the plane is whole again. s is the middle of the seam: with its left
  // neighbour it has two triangles and two common neighbours; the seam edge up from it has
  // one triangle each side, and two common neighbours.
  CHECK(g.welded_link_ok(f, s, left, 2, false));
  CHECK_FALSE(g.welded_link_ok(f, s, left, 1, false));
  CHECK(g.welded_link_ok(f, s, s_up, 2, true));
  // Not along the seam, the seam edge's twin is a second contact between the groups.
  CHECK_FALSE(g.welded_link_ok(f, s, s_up, 2, false));
  // s and a right vertex: no split edge, but s's twin neighbours it.
  CHECK(g.group_of[twin_s] == g.group_of[s]);
  CHECK_FALSE(g.welded_link_ok(f, s, right, 2, false));
  CHECK(g.welded_link_ok(f, twin_s, right, 2, false));
  // A collapse into a twin makes the neighbours it gains neighbours of the seam.
  const uint32_t far_left = at(m, -1, 0);
  CHECK_FALSE(g.near_seam[far_left]);
  g.note_collapse(f, s, left);
  CHECK(g.near_seam[far_left]);
}

TEST_CASE("seam groups: position_vertex of the output", "[simplify]") {
  Mesh in;
  in.positions.assign(15, 0.f);
  in.position_vertex = {0, 1, 0, 3, 1};
  Mesh out;
  // Survivors 1, 2, 4 (input ids): 2 is 0's twin with 0 gone, 4 is 1's twin.
  detail::write_position_vertex(in, {1, 2, 4}, &out);
  CHECK(out.position_vertex == std::vector<uint32_t>{0, 1, 0});
  // No group kept two members: no position_vertex at all.
  detail::write_position_vertex(in, {1, 2, 3}, &out);
  CHECK(out.position_vertex.empty());
}
