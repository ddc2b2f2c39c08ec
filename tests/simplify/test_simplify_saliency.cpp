// Saliency-guided simplification keeps the unique feature of the bumpy sphere better than
// the plain quadric method at the same face count (the paper's section 4 claim).
#include <cmath>

#include "core/mesh_points.h"
#include "saliency/saliency.h"
#include "simplify/saliency_weights.h"
#include "simplify/simplify.h"
#include "core/surface_distance.h"
#include "cli/synthetic.h"
#include "test_util.h"

using namespace meshsal;

static double mean_distance(const Mesh& original, const std::vector<uint8_t>& mask,
                            const Mesh& simplified) {
  const TriangleBvh bvh = build_triangle_bvh(simplified);
  double sum = 0;
  size_t n = 0;
  for (size_t v = 0; v < original.vertex_count(); ++v) {
    if (!mask[v]) continue;
    const double p[3] = {original.positions[3 * v], original.positions[3 * v + 1],
                         original.positions[3 * v + 2]};
    sum += surface_distance(bvh, p);
    ++n;
  }
  REQUIRE(n > 0);
  return sum / double(n);
}

TEST_CASE("simplify: saliency weights keep the unique feature of the bumpy sphere",
          "[simplify]") {
  std::vector<uint8_t> feature;
  const Mesh m = make_bumpy_sphere(5, &feature);
  SaliencyOptions so;
  so.smoothed = true;
  const SaliencyResult s = compute_saliency_cpu(m, so);
  REQUIRE(s.smoothed.size() == m.vertex_count());
  const SaliencyWeights sw = saliency_weights(s.smoothed, s.is_point, {});
  const std::vector<double>& w = sw.weights;
  CHECK(sw.alpha > 0);
  for (size_t faces : {size_t(2000), size_t(4000)}) {
    SimplifyOptions o;
    o.target_faces = faces;
    const Mesh plain = simplify_mesh(m, o).mesh;
    const Mesh guided = simplify_mesh(m, o, w).mesh;
    REQUIRE(plain.triangle_count() == faces);
    REQUIRE(guided.triangle_count() == faces);
    const double e_plain = mean_distance(m, feature, plain);
    const double e_guided = mean_distance(m, feature, guided);
    INFO(faces << " faces: feature error plain " << e_plain << ", saliency " << e_guided);
    CHECK(e_guided < 0.8 * e_plain);
  }
}

TEST_CASE("saliency weights: percentile threshold and amplification", "[simplify]") {
  const std::vector<double> sm{0.0, 1.0, 2.0, 3.0, 4.0, 5.0};
  const std::vector<uint8_t> all(6, 1);
  CHECK(percentile(sm, all, 0) == 0.0);
  CHECK(percentile(sm, all, 100) == 5.0);
  CHECK(percentile(sm, all, 30) == Approx(1.5));
  SaliencyWeightOptions o;  // lambda 100, 30th percentile
  o.floor = 0;              // the paper's literal rule (the default floor is tested below)
  SaliencyWeights sw = saliency_weights(sm, all, o);
  std::vector<double> w = sw.weights;
  CHECK(sw.alpha == Approx(1.5));
  const std::vector<double> expected{0.0, 1.0, 200.0, 300.0, 400.0, 500.0};
  for (size_t i = 0; i < w.size(); ++i) CHECK(w[i] == Approx(expected[i]));
  // Vertices that are not mesh points get 0 and do not count for the percentile.
  std::vector<uint8_t> mask{1, 1, 1, 1, 1, 0};
  sw = saliency_weights({1.0, 1.0, 1.0, 1.0, 2.0, 9.0}, mask, o);
  w = sw.weights;
  CHECK(sw.alpha == Approx(1.0));
  CHECK(w[5] == 0.0);
  CHECK(w[0] == Approx(100.0));  // Sm >= alpha is amplified
  // A floor lifts near-zero weights.
  o.floor = 0.5;
  w = saliency_weights(sm, all, o).weights;
  CHECK(w[0] == Approx(0.5 * (0 + 1 + 200 + 300 + 400 + 500) / 6.0));
  CHECK(w[5] == Approx(500.0));
  CHECK_THROWS(saliency_weights({1.0}, all, {}).weights);
  CHECK_THROWS(percentile(sm, all, 101));
}
