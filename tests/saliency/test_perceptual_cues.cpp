// The perceptual model's cues without views (saliency/perceptual_cues.h): height along the
// up axis, and global rarity, by hand on a small case and on the demo sphere, whose one
// unique feature must be rarer than its ~900 repeated bumps.
#include <cmath>

#include "cli/synthetic.h"
#include "core/mesh_points.h"
#include "meshsal/meshsal.h"
#include "saliency/curvature.h"
#include "saliency/gaussian_filter.h"
#include "saliency/perceptual_cues.h"
#include "test_util.h"

using namespace meshsal;

TEST_CASE("height runs from 0 at the lowest mesh point to 1 at the highest along up") {
  Mesh m = make_sphere(2.0, 2);
  m.positions.insert(m.positions.end(), {0.0f, 50.0f, 0.0f});  // not a mesh point
  const std::vector<uint8_t> is_point = referenced_vertices(m);
  const double up_y[3] = {0, 1, 0}, down_z[3] = {0, 0, -1};
  const std::vector<double> h = height_cue(m, is_point, up_y);
  const std::vector<double> d = height_cue(m, is_point, down_z);
  for (size_t i = 0; i + 1 < m.vertex_count(); ++i) {
    CHECK(h[i] == Approx((m.positions[3 * i + 1] + 2.0) / 4.0).margin(1e-6));
    CHECK(d[i] == Approx((2.0 - m.positions[3 * i + 2]) / 4.0).margin(1e-6));
  }
  CHECK(h.back() == 0.0);
}

TEST_CASE("global rarity is the self-information of each point's joint bin") {
  // One dimension, ten points: nine at 0 and one at 1. The 0.5th and 99.5th percentiles
  // are 0 and 1, so the nine share the first bin and the one sits in the last.
  std::vector<double> col(10, 0.0);
  col[7] = 1.0;
  std::vector<uint8_t> is_point(10, 1);
  std::vector<double> r = global_rarity({col}, is_point);
  for (size_t i = 0; i < 10; ++i) CHECK(r[i] == Approx(i == 7 ? std::log(10.0) : std::log(10.0 / 9.0)));
  // Two dimensions: the marginals alone are common, the pair is what is rare.
  std::vector<double> a = {0, 0, 0, 0, 1, 1, 1, 1}, b = {0, 0, 0, 1, 1, 1, 1, 0};
  r = global_rarity({a, b}, std::vector<uint8_t>(8, 1));
  CHECK(r[0] == Approx(std::log(8.0 / 3)));  // (0, 0) three times
  CHECK(r[3] == Approx(std::log(8.0)));      // (0, 1) once
  CHECK(r[7] == Approx(std::log(8.0)));      // (1, 0) once
  CHECK(r[4] == Approx(std::log(8.0 / 3)));  // (1, 1) three times
  // Vertices that are not mesh points get 0 and count for nothing.
  std::vector<uint8_t> some(10, 1);
  some[7] = 0;
  r = global_rarity({col}, some);
  CHECK(r[7] == 0.0);
  CHECK(r[0] == Approx(0.0).margin(1e-12));  // every point alike: no information
}

TEST_CASE("the unique feature of the demo sphere is rarer than its repeated bumps") {
  std::vector<uint8_t> feature, bumps;
  const Mesh m = make_bumpy_sphere(5, &feature, &bumps);
  const std::vector<uint8_t> is_point = referenced_vertices(m);
  const double eps = scale_unit(m, is_point, 0.003);
  std::vector<double> sigmas;
  for (double k : rarity_descriptor_scales()) sigmas.push_back(k * eps);
  const std::vector<double> h = mean_curvature_morton(m, mesh_points_bbox(m, is_point));
  const std::vector<double> r = global_rarity(gaussian_filter(m, is_point, h, sigmas), is_point);
  const double on_feature = meshsal_test::mean_over(r, feature), on_bumps = meshsal_test::mean_over(r, bumps);
  INFO("rarity on the feature " << on_feature << ", on the bumps " << on_bumps);
  CHECK(on_feature > 1.5 * on_bumps);
}
