// Taubin mean curvature against analytic values (SPEC 1).
#include <algorithm>
#include <cmath>
#include <cstring>
#include <vector>

#include "core/adjacency.h"
#include "saliency/curvature.h"
#include "cli/synthetic.h"
#include "test_util.h"

using namespace meshsal;

TEST_CASE("curvature of a sphere is -1/r within 2%", "[curvature]") {
  const double r = 2.5;
  Mesh sphere = make_sphere(r, 5);  // 10242 vertices
  auto H = mean_curvature(sphere, build_adjacency(sphere), vertex_normals(sphere));
  double worst = 0;
  for (double h : H) worst = std::max(worst, std::fabs(h * r + 1.0));  // outward normals: H = -1/r
  INFO("worst relative error " << worst);
  CHECK(worst < 0.02);
}

TEST_CASE("curvature of a plane is zero", "[curvature]") {
  Mesh plane = make_plane(3.0, 40);
  auto H = mean_curvature(plane, build_adjacency(plane), vertex_normals(plane));
  for (double h : H) REQUIRE(std::fabs(h) < 1e-12);
}

TEST_CASE("curvature skips unreferenced vertices and degenerate triangles", "[curvature]") {
  Mesh m = make_sphere(1.0, 3);
  const size_t extra = m.vertex_count();
  m.positions.insert(m.positions.end(), {5.f, 5.f, 5.f});  // unreferenced
  m.triangles.insert(m.triangles.end(), {0, 0, 1});        // zero-area triangle
  auto adj = build_adjacency(m);
  auto H = mean_curvature(m, adj, vertex_normals(m));
  CHECK(H[extra] == 0.0);
  CHECK(std::fabs(H[0] + 1.0) < 0.05);
  // The zero-area triangle adds no self edge and no area.
  for (uint32_t e = adj.offsets[0]; e < adj.offsets[1]; ++e) CHECK(adj.neighbors[e] != 0);
}

TEST_CASE("adjacency sums the area of both triangles on an edge", "[curvature]") {
  // Two right triangles of area 0.5 sharing the diagonal 0-2 of the unit square.
  Mesh m;
  m.positions = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
  m.triangles = {0, 1, 2, 0, 2, 3};
  Adjacency adj = build_adjacency(m);
  REQUIRE(adj.offsets[1] - adj.offsets[0] == 3);  // 0: neighbours 1, 2, 3
  CHECK(adj.neighbors[adj.offsets[0] + 1] == 2);
  CHECK(adj.edge_area[adj.offsets[0] + 1] == Approx(1.0));
  CHECK(adj.edge_area[adj.offsets[0]] == Approx(0.5));
}

TEST_CASE("mean_curvature_at gives the listed vertices mean_curvature's bits", "[curvature]") {
  // A bumpy sphere with extra triangles: degenerate, repeated, reversed, non-manifold, and
  // a loose vertex; every fifth vertex listed (and the loose one), in no particular order.
  Mesh m = make_bumpy_sphere(3);
  const uint32_t n = uint32_t(m.vertex_count());
  m.positions.insert(m.positions.end(), {0.1f, 0.2f, 0.3f, 3.0f, 1.0f, -2.0f});
  m.triangles.insert(m.triangles.end(), {0, 0, 5, 1, 2, 1, 3, 4, 5, 3, 4, 5, 5, 4, 3, 3, 4, n + 1, 7, 8, 8});
  const std::vector<double> all = mean_curvature(m, build_adjacency(m), vertex_normals(m));
  std::vector<uint32_t> listed{n};
  for (uint32_t v = 0; v < m.vertex_count(); ++v)
    if (v % 5 == 0 || v < 9) listed.push_back(v);  // 0: the (0, 0, 5) triangle's
  std::reverse(listed.begin() + 1, listed.end());
  std::vector<double> H(m.vertex_count(), -7.0);
  mean_curvature_at(m, listed, H.data());
  size_t same = 0, untouched = 0;
  for (uint32_t v = 0; v < m.vertex_count(); ++v) {
    const bool is_listed = std::find(listed.begin(), listed.end(), v) != listed.end();
    if (is_listed) same += std::memcmp(&H[v], &all[v], 8) == 0;
    else untouched += H[v] == -7.0;
  }
  CHECK(same == listed.size());
  CHECK(untouched == m.vertex_count() - listed.size());
  // Not a comparison of zeros: every listed vertex but the loose one has a curvature.
  size_t curved = 0;
  for (uint32_t v : listed) curved += all[v] != 0.0;
  CHECK(curved + 1 == listed.size());
}
