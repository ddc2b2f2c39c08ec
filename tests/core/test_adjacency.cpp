// The parallel 1-ring builder against its serial oracle (one sorted list of all half-edges).
#include <cmath>

#include "core/adjacency.h"
#include "cli/synthetic.h"
#include "test_util.h"

using namespace meshsal;

namespace {

void require_same(const Adjacency& a, const Adjacency& b) {
  REQUIRE(a.offsets == b.offsets);
  REQUIRE(a.neighbors == b.neighbors);
  REQUIRE(a.edge_area.size() == b.edge_area.size());
  for (size_t e = 0; e < a.edge_area.size(); ++e) REQUIRE(a.edge_area[e] == b.edge_area[e]);
}

// A sphere with every awkward case added: an unreferenced vertex, degenerate triangles
// (a repeated corner, three equal corners), an edge shared by four triangles with areas
// whose sum depends on the order, and a fan of 40 triangles around one vertex (80
// half-edges: the stable_sort branch).
Mesh awkward_mesh() {
  Mesh m = make_sphere(1.0, 2);
  auto add = [&](float x, float y, float z) {
    m.positions.insert(m.positions.end(), {x, y, z});
    return uint32_t(m.vertex_count() - 1);
  };
  add(9, 9, 9);  // unreferenced
  m.triangles.insert(m.triangles.end(), {0, 0, 1, 2, 2, 2, 3, 4, 3});
  const uint32_t a = add(3, 0, 0), b = add(3, 1, 0);
  const float tip[4][3] = {{3.1f, 0.5f, 1}, {2.3f, 0.5f, -0.7f}, {3.7f, 0.3f, 1e-3f}, {3, 0.5f, 1e4f}};
  for (const auto& p : tip) m.triangles.insert(m.triangles.end(), {a, b, add(p[0], p[1], p[2])});
  const uint32_t hub = add(-3, 0, 0);
  uint32_t first = add(-3, 1, 0), prev = first;
  for (int i = 1; i < 40; ++i) {
    const double angle = 2 * M_PI * i / 40;
    const uint32_t next = add(-3, float(std::cos(angle) * (1 + 0.1 * (i % 3))), float(std::sin(angle)));
    m.triangles.insert(m.triangles.end(), {hub, prev, next});
    prev = next;
  }
  m.triangles.insert(m.triangles.end(), {hub, prev, first});
  return m;
}

}  // namespace

TEST_CASE("adjacency: the parallel builder equals the oracle on awkward meshes", "[curvature]") {
  const Mesh m = awkward_mesh();
  const Adjacency want = build_adjacency_reference(m);
  const uint32_t hub = uint32_t(m.vertex_count() - 41);
  REQUIRE(want.offsets[hub + 1] - want.offsets[hub] == 40);  // the fan
  REQUIRE(want.offsets[m.vertex_count() - 48] == want.offsets[m.vertex_count() - 47]);  // unreferenced
  for (unsigned threads : {1u, 2u, 3u, 8u}) {
    INFO("threads " << threads);
    require_same(build_adjacency(m, threads), want);
  }
}

TEST_CASE("adjacency: an edge's area sums its triangles in triangle order", "[curvature]") {
  // Three triangles on the edge 0-1 with exact areas 1, 2^-53, 2^-53: in triangle order
  // (1 + 2^-53) + 2^-53 rounds to 1 twice; small ones first would give 1 + 2^-52.
  const float h = std::ldexp(1.0f, -52);
  Mesh m;
  m.positions = {0, 0, 0, 1, 0, 0, 0, 2, 0, 0, 0, h, 0, -h, 0};
  m.triangles = {0, 1, 2, 0, 1, 3, 1, 0, 4};
  for (unsigned threads : {1u, 2u}) {
    const Adjacency adj = build_adjacency(m, threads);
    REQUIRE(adj.offsets[1] - adj.offsets[0] == 4);  // 0: neighbours 1, 2, 3, 4
    REQUIRE(adj.neighbors[adj.offsets[0]] == 1);
    CHECK(adj.edge_area[adj.offsets[0]] == 1.0);
    CHECK(adj.edge_area[adj.offsets[0] + 1] == 1.0);  // 0-2: one triangle
    CHECK(adj.edge_area[adj.offsets[0] + 2] == std::ldexp(1.0, -53));
    require_same(adj, build_adjacency_reference(m));
  }
}

TEST_CASE("adjacency: the parallel builder equals the oracle on a scan", "[curvature]") {
  MESHSAL_REQUIRE_MESH(path, "bunny_3k.off");
  const Mesh m = load_mesh(path);
  require_same(build_adjacency(m, 2), build_adjacency_reference(m));
}

TEST_CASE("adjacency: the same lists when the vertices are split among threads", "[curvature]") {
  // Over 2 x 64K vertices, so that each thread owns a range of them and scans every triangle
  // for its corners (the triangles around each vertex); a triangle's corners lie in
  // different ranges, and the awkward cases sit at the end.
  Mesh m = make_sphere(1.0, 7);
  const Mesh extra = awkward_mesh();
  const uint32_t base = uint32_t(m.vertex_count());
  REQUIRE(base > 2 * 65536);
  m.positions.insert(m.positions.end(), extra.positions.begin(), extra.positions.end());
  for (uint32_t i : extra.triangles) m.triangles.push_back(base + i);
  m.triangles.insert(m.triangles.end(), {0, base - 1, base + 5, base / 2, 7, base + 40});
  const Adjacency want = build_adjacency_reference(m);
  for (unsigned threads : {1u, 2u, 3u}) {
    INFO("threads " << threads);
    require_same(build_adjacency(m, threads), want);
  }
}
