// Library functions refuse numbers that make no sense (a library user has no CLI checks in
// front): `scales = {1e300}` gave an all-zero saliency map before.
#include <cmath>
#include <limits>

#include "meshsal/meshsal.h"
#include "saliency/saliency.h"
#include "simplify/saliency_weights.h"
#include "cli/synthetic.h"
#include "test_util.h"

using namespace meshsal;

TEST_CASE("saliency options out of range throw meshsal::Error", "[saliency]") {
  const Mesh mesh = make_sphere(1.0, 2);
  SaliencyOptions o;
  o.scales = {1e300};
  CHECK_THROWS_WITH(compute_saliency_cpu(mesh, o), "scales must be finite numbers in (0, 100], got 1e+300");
  CHECK_THROWS_AS(compute_saliency(mesh, o), Error);
  o.scales = {2, std::numeric_limits<double>::quiet_NaN()};
  CHECK_THROWS_AS(compute_saliency_cpu(mesh, o), Error);
  o = {};
  o.eps_frac = std::numeric_limits<double>::infinity();
  CHECK_THROWS_WITH(compute_saliency_cpu(mesh, o), "eps-frac must be a finite number in (0, 0.1], got inf");
  o = {};
  o.scales = {50};
  o.eps_frac = 0.05;  // surround sigma 2 x 50 x 0.05 = 5 diagonals
  CHECK_THROWS_WITH(compute_saliency_cpu(mesh, o), Catch::StartsWith("scales and eps-frac: the widest surround sigma"));
  o = {};
  CHECK_NOTHROW(check_saliency_options(o));
  CHECK_THROWS_WITH(parse_scales("2,1e300"), "scales must be a comma-separated list of numbers in (0, 100], got '2,1e300'");

  std::vector<double> s(mesh.vertex_count(), 1.0);
  CHECK_THROWS_WITH(smooth_saliency(mesh, s, 0.0), "eps-frac must be a finite number in (0, 0.1], got 0");
  const std::vector<uint8_t> all(mesh.vertex_count(), 1);
  SaliencyWeightOptions w;
  w.lambda = 1e300;
  CHECK_THROWS_WITH(saliency_weights(s, all, w).weights, "lambda must be a finite number in [0, 1e+06]");
  w.lambda = 100;
  w.floor = std::numeric_limits<double>::infinity();
  CHECK_THROWS_WITH(saliency_weights(s, all, w).weights, "weight floor must be a finite number in [0, 100]");
}
