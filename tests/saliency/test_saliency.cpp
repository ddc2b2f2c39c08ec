// Saliency end to end on synthetic meshes: the analytic cases and the paper's claim.
#include <cmath>

#include "meshsal/meshsal.h"
#include "saliency/saliency.h"
#include "cli/synthetic.h"
#include "test_util.h"

using namespace meshsal;
using meshsal_test::check_sphere_raw_maps;
using meshsal_test::mean_over;

TEST_CASE("sphere: raw center-surround maps are below 1% of |H|", "[saliency]") {
  const double r = 3.0;
  check_sphere_raw_maps(compute_saliency_cpu(make_sphere(r, 5), {}), r);
}

TEST_CASE("plane: curvature and saliency are zero", "[saliency]") {
  SaliencyResult s = compute_saliency_cpu(make_plane(2.0, 30), {});
  for (size_t v = 0; v < s.saliency.size(); ++v) {
    REQUIRE(s.curvature[v] == 0.0);
    REQUIRE(s.saliency[v] == 0.0);
  }
}

TEST_CASE("plane with one bump: the saliency maximum away from the border is on the bump",
          "[saliency]") {
  const double size = 4.0, width = 0.12;
  Mesh m = make_plane_with_bump(size, 160, 0.15, width);
  SaliencyResult s = compute_saliency_cpu(m, {});
  size_t best = 0;
  double best_value = -1;
  for (size_t v = 0; v < m.vertex_count(); ++v) {
    double x = m.positions[3 * v], y = m.positions[3 * v + 1];
    if (std::fabs(x) > 0.4 * size || std::fabs(y) > 0.4 * size) continue;  // away from the border
    if (s.saliency[v] > best_value) best_value = s.saliency[v], best = v;
  }
  double x = m.positions[3 * best], y = m.positions[3 * best + 1];
  INFO("maximum " << best_value << " at (" << x << ", " << y << ")");
  CHECK(best_value > 0);
  CHECK(std::hypot(x, y) < 3 * width);
}

TEST_CASE("bumpy sphere: the unique feature beats the repeated bumps, curvature does not",
          "[saliency]") {
  std::vector<uint8_t> feature, bumps;
  Mesh m = make_bumpy_sphere(6, &feature, &bumps);
  SaliencyResult s = compute_saliency_cpu(m, {});
  const double feature_saliency = mean_over(s.saliency, feature);
  const double bump_saliency = mean_over(s.saliency, bumps);
  const double feature_curvature = mean_over(s.curvature, feature, true);
  const double bump_curvature = mean_over(s.curvature, bumps, true);
  INFO("saliency: feature " << feature_saliency << ", bumps " << bump_saliency);
  INFO("|H|: feature " << feature_curvature << ", bumps " << bump_curvature);
  CHECK(feature_saliency > 1.5 * bump_saliency);
  CHECK(bump_curvature >= feature_curvature);
}

TEST_CASE("saliency output keeps vertex order and zeroes unreferenced vertices", "[saliency]") {
  Mesh m = make_bumpy_sphere(3);
  SaliencyResult base = compute_saliency_cpu(m, {});
  // Prepend an unreferenced vertex: every index shifts by one, results must shift with it.
  Mesh shifted;
  shifted.positions = {9.f, 9.f, 9.f};
  shifted.positions.insert(shifted.positions.end(), m.positions.begin(), m.positions.end());
  for (uint32_t i : m.triangles) shifted.triangles.push_back(i + 1);
  SaliencyResult s = compute_saliency_cpu(shifted, {});
  CHECK(s.saliency[0] == 0.0);
  CHECK(s.curvature[0] == 0.0);
  CHECK(s.eps == Approx(base.eps).epsilon(1e-12));
  for (size_t v = 0; v < m.vertex_count(); ++v)
    REQUIRE(s.saliency[v + 1] == Approx(base.saliency[v]).margin(1e-9));
}

TEST_CASE("scale parsing accepts lists and rejects junk", "[saliency]") {
  CHECK(parse_scales("2,3,4,5,6") == std::vector<double>{2, 3, 4, 5, 6});
  CHECK(parse_scales("1.5") == std::vector<double>{1.5});
  CHECK_THROWS_AS(parse_scales(""), Error);
  CHECK_THROWS_AS(parse_scales("2,,3"), Error);
  CHECK_THROWS_AS(parse_scales("2,-1"), Error);
  CHECK_THROWS_AS(parse_scales("two"), Error);
  CHECK(filter_sigma_units({2, 3, 4, 5, 6}) == std::vector<double>{2, 3, 4, 5, 6, 8, 10, 12});
}
