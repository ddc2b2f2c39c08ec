// The simplifier's triangle fans (src/simplify/triangle_fans.*): after building and after
// every merge, each vertex's fan holds exactly its live triangles (compared with a scan of
// all triangles), through fans that outgrow their room and repacks of the pool.
#include <catch2/catch.hpp>

#include <random>
#include <set>
#include <vector>

#include "cli/synthetic.h"
#include "simplify/triangle_fans.h"

using namespace meshsal;
using detail::TriangleFans;

namespace {

// v's live triangles from its fan, and from a scan of every triangle.
std::multiset<uint32_t> live_fan(const TriangleFans& f, uint32_t v) {
  std::multiset<uint32_t> s;
  for (uint32_t t : f.fan(v))
    if (f.live[t]) s.insert(t);
  return s;
}
std::multiset<uint32_t> scanned(const TriangleFans& f, uint32_t v) {
  std::multiset<uint32_t> s;
  for (uint32_t t = 0; t < f.triangle_count(); ++t) {
    const uint32_t* c = f.corners_of(t);
    if (f.live[t] && (c[0] == v || c[1] == v || c[2] == v)) s.insert(t);
  }
  return s;
}

}  // namespace

TEST_CASE("triangle fans hold each vertex's live triangles through merges and repacks", "[simplify]") {
  const Mesh m = make_sphere(1.0, 2);
  const size_t nv = m.vertex_count();
  TriangleFans f;
  f.corners = m.triangles;
  f.build(nv);
  std::vector<uint8_t> vertex_live(nv, 1);
  for (uint32_t v = 0; v < nv; ++v) REQUIRE(live_fan(f, v) == scanned(f, v));
  REQUIRE(f.fan_size(0) == 5);  // an icosahedron corner
  std::mt19937 rng(3);
  size_t faces = f.triangle_count(), moves = 0;
  const size_t pool_at_start = f.pool.size();
  for (int step = 0; step < 250 && faces > 40; ++step) {
    // Any edge of a live triangle: no link condition here, the fans must stay right anyway.
    uint32_t t;
    do t = std::uniform_int_distribution<uint32_t>(0, uint32_t(f.triangle_count() - 1))(rng);
    while (!f.live[t]);
    const uint32_t a = f.corners_of(t)[0], b = f.corners_of(t)[1];
    size_t on_edge = 0;
    for (uint32_t x : scanned(f, a)) on_edge += scanned(f, b).count(x);
    const uint32_t start_a = f.place[a].start;
    const size_t died = f.merge(a, b, vertex_live);
    vertex_live[b] = 0;
    moves += f.place[a].start != start_a;
    CHECK(died == on_edge);
    faces -= died;
    CHECK(f.fan_size(b) == 0);
    for (uint32_t x : f.fan(a)) CHECK(f.live[x]);  // merge compacts a
    // b is gone from every live triangle; every fan is still exact.
    CHECK(scanned(f, b).empty());
    for (uint32_t v = 0; v < nv; ++v)
      if (vertex_live[v]) REQUIRE(live_fan(f, v) == scanned(f, v));
  }
  size_t live = 0;
  for (uint8_t x : f.live) live += x;
  CHECK(live == faces);
  CHECK(moves > 0);  // some fans outgrew their room
  CHECK(f.pool.size() != pool_at_start);
  // A repack keeps every fan (live triangles only) and drops the dead vertices' ones.
  f.repack(vertex_live);
  for (uint32_t v = 0; v < nv; ++v) {
    if (vertex_live[v]) CHECK(live_fan(f, v) == scanned(f, v));
    if (vertex_live[v]) CHECK(f.fan_size(v) == scanned(f, v).size());
    if (!vertex_live[v]) CHECK(f.fan_size(v) == 0);
  }
}

TEST_CASE("triangle fans: compact drops dead triangles in order", "[simplify]") {
  TriangleFans f;
  f.corners = {0, 1, 2, 0, 2, 3, 0, 3, 4, 0, 4, 1};  // a fan of four around vertex 0
  f.build(5);
  CHECK(std::vector<uint32_t>(f.fan(0).begin(), f.fan(0).end()) == std::vector<uint32_t>{0, 1, 2, 3});
  f.live[1] = f.live[3] = 0;
  f.compact(0);
  CHECK(std::vector<uint32_t>(f.fan(0).begin(), f.fan(0).end()) == std::vector<uint32_t>{0, 2});
}
