// The grid sweep against the all-pairs oracle, both in double (SPEC 1).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>

#include "core/adjacency.h"
#include "saliency/curvature.h"
#include "saliency/gaussian_filter.h"
#include "meshsal/meshsal.h"
#include "core/mesh_points.h"
#include "saliency/saliency.h"
#include "cli/synthetic.h"
#include "test_util.h"

using namespace meshsal;

static void check_against_bruteforce(const Mesh& mesh, const std::vector<double>& units) {
  auto is_point = referenced_vertices(mesh);
  const double eps = scale_unit(mesh, is_point, 0.003);
  auto H = mean_curvature(mesh, build_adjacency(mesh), vertex_normals(mesh));
  std::vector<double> sigmas;
  for (double u : units) sigmas.push_back(u * eps);
  FilterStats stats;
  auto fast = gaussian_filter(mesh, is_point, H, sigmas, 2, &stats);
  auto slow = gaussian_filter_bruteforce(mesh, is_point, H, sigmas);
  REQUIRE(fast.size() == sigmas.size());
  // The sweep visits exactly the pairs inside the largest cutoff: not the candidates of the
  // grid rows it walks (~1.4x as many), not a pair twice, none missed. A pair within a few
  // ulps of the cutoff may fall either side (the sweep subtracts the grid origin first).
  const uint64_t expected = meshsal_test::pairs_within(mesh, is_point, 2 * *std::max_element(sigmas.begin(), sigmas.end()));
  INFO("pairs: sweep " << stats.pairs << ", counted " << expected);
  CHECK(expected > 2 * mesh.vertex_count());  // neighbours, not only each point itself
  CHECK(std::llabs(int64_t(stats.pairs) - int64_t(expected)) <= int64_t(expected / 1000000));
  for (size_t k = 0; k < sigmas.size(); ++k) {
    double scale = 0, worst = 0;
    for (double x : slow[k]) scale = std::max(scale, std::fabs(x));
    REQUIRE(scale > 0);
    for (size_t v = 0; v < mesh.vertex_count(); ++v)
      worst = std::max(worst, std::fabs(fast[k][v] - slow[k][v]));
    INFO("sigma " << units[k] << " eps: worst difference " << worst << " of max " << scale);
    CHECK(worst <= 1e-9 * scale);
  }
}

TEST_CASE("grid sweep equals brute force on a bumpy sphere, all eight sigmas", "[filter]") {
  check_against_bruteforce(make_bumpy_sphere(3), filter_sigma_units({2, 3, 4, 5, 6}));
}

TEST_CASE("grid sweep equals brute force on a plane with a bump", "[filter]") {
  check_against_bruteforce(make_plane_with_bump(2.0, 50, 0.2, 0.15), {2, 3, 4, 5, 6, 8, 10, 12});
}

TEST_CASE("grid sweep equals brute force for sigmas without a 2x partner", "[filter]") {
  check_against_bruteforce(make_cube(14), {1.5, 3, 7, 13});
}

TEST_CASE("grid sweep equals brute force on a real scan", "[filter]") {
  MESHSAL_REQUIRE_MESH(path, "bunny_3k.off");
  Mesh mesh = load_mesh(path);
  check_against_bruteforce(mesh, filter_sigma_units({2, 3, 4, 5, 6}));
}

TEST_CASE("filter ignores unreferenced vertices", "[filter]") {
  Mesh m = make_sphere(1.0, 2);
  const size_t extra = m.vertex_count();
  m.positions.insert(m.positions.end(), {0.f, 0.f, 1.01f});  // close to the surface, unreferenced
  auto is_point = referenced_vertices(m);
  std::vector<double> values(m.vertex_count(), 1.0);
  values[extra] = 1000.0;  // would pull averages up if it took part
  auto G = gaussian_filter(m, is_point, values, {0.3});
  CHECK(G[0][extra] == 0.0);
  for (size_t v = 0; v < extra; ++v) REQUIRE(G[0][v] == Approx(1.0).epsilon(1e-12));
}
