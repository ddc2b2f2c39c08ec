// The perceptual model through compute_saliency (api/perceptual_model.cpp): its known
// answers (a protrusion near the top outranks the same near the bottom, a sphere hidden
// inside another gets nothing), the cues alone equal to their functions, the same bits on
// any thread count, the fast method close to the exact, and what it refuses.
#include <algorithm>
#include <cmath>

#include "cli/synthetic.h"
#include "core/mesh_points.h"
#include "meshsal/meshsal.h"
#include "saliency/perceptual_cues.h"
#include "test_util.h"

using namespace meshsal;

namespace {

SaliencyOptions model_options(Model model, unsigned threads = 0) {
  SaliencyOptions o;
  o.model = model;
  o.threads = threads;
  return o;
}

// A cube (side 2, y up) with two equal Gaussian bumps on its front face (z = 1), one near
// the top and one as far below the middle. mask: 1 near the upper bump, 2 near the lower.
Mesh cube_with_two_bumps(std::vector<uint8_t>* mask) {
  Mesh m = make_cube(48);
  mask->assign(m.vertex_count(), 0);
  for (size_t i = 0; i < m.vertex_count(); ++i) {
    float* p = &m.positions[3 * i];
    if (p[2] != 1.0f) continue;
    for (int k = 0; k < 2; ++k) {
      const float y0 = k == 0 ? 0.55f : -0.55f;
      const float d2 = p[0] * p[0] + (p[1] - y0) * (p[1] - y0);
      p[2] += 0.25f * std::exp(-d2 / (2 * 0.1f * 0.1f));
      if (d2 < 0.15f * 0.15f) (*mask)[i] = uint8_t(k + 1);
    }
  }
  return m;
}

double mean_where(const std::vector<double>& v, const std::vector<uint8_t>& mask, uint8_t which) {
  double sum = 0;
  size_t n = 0;
  for (size_t i = 0; i < v.size(); ++i)
    if (mask[i] == which) sum += v[i], ++n;
  REQUIRE(n > 0);
  return sum / double(n);
}

}  // namespace

TEST_CASE("perceptual: a protrusion near the top outranks the same near the bottom") {
  std::vector<uint8_t> mask;
  const Mesh m = cube_with_two_bumps(&mask);
  const SaliencyResult s = compute_saliency(m, model_options(Model::Perceptual));
  const double top = mean_where(s.saliency, mask, 1), bottom = mean_where(s.saliency, mask, 2);
  INFO("S near the upper bump " << top << ", near the lower " << bottom);
  CHECK(top > 1.2 * bottom);
  // The paper's saliency has no such preference: the two bumps are alike.
  const SaliencyResult lee = compute_saliency(m, SaliencyOptions{});
  CHECK(mean_where(lee.saliency, mask, 1) == Approx(mean_where(lee.saliency, mask, 2)).epsilon(0.05));
}

TEST_CASE("perceptual: a sphere hidden inside another gets nothing and S tops at 1") {
  Mesh both = make_sphere(1.0, 3);
  const Mesh inner = make_sphere(0.5, 3);
  const size_t outer_n = both.vertex_count();
  for (float x : inner.positions) both.positions.push_back(x);
  for (uint32_t t : inner.triangles) both.triangles.push_back(uint32_t(outer_n) + t);
  const SaliencyResult s = compute_saliency(both, model_options(Model::Perceptual));
  REQUIRE(s.model == Model::Perceptual);
  double inner_max = 0, outer_max = 0;
  for (size_t i = 0; i < both.vertex_count(); ++i) {
    CHECK(s.saliency[i] >= 0);
    (i < outer_n ? outer_max : inner_max) = std::max(i < outer_n ? outer_max : inner_max, s.saliency[i]);
  }
  CHECK(outer_max == Approx(1.0));
  // Unseen, and beyond the smoothing's cutoff (2 x 0.05 x the diagonal 3.46 < 0.5) from the outer sphere.
  CHECK(inner_max == 0.0);
  // The cues, named as the models, one value per vertex.
  REQUIRE(s.cues.size() == 4);
  const char* names[] = {"exposure", "height", "rarity", "coarse"};
  for (size_t k = 0; k < 4; ++k) {
    CHECK(s.cues[k].first == names[k]);
    CHECK(s.cues[k].second.size() == both.vertex_count());
  }
}

TEST_CASE("a cue alone is its function scaled to a maximum of 1") {
  const Mesh m = make_bumpy_sphere(3);
  const std::vector<uint8_t> is_point = referenced_vertices(m);
  const SaliencyResult h = compute_saliency(m, model_options(Model::Height));
  const double up[3] = {0, 1, 0};
  CHECK(h.saliency == height_cue(m, is_point, up));
  SaliencyOptions coarse = model_options(Model::Coarse);
  const SaliencyResult c = compute_saliency(m, coarse);
  SaliencyOptions twice;
  twice.scales = {4, 6, 8, 10, 12};
  std::vector<double> lee = compute_saliency(m, twice).saliency;
  scale_to_max(lee, is_point);
  CHECK(c.saliency == lee);
  for (Model model : {Model::Exposure, Model::Centre, Model::Rarity}) {
    const SaliencyResult r = compute_saliency(m, model_options(model));
    INFO(model_name(model));
    CHECK(*std::max_element(r.saliency.begin(), r.saliency.end()) == Approx(1.0));
    CHECK(*std::min_element(r.saliency.begin(), r.saliency.end()) >= 0.0);
    REQUIRE(r.cues.size() == 1);
    CHECK(r.cues[0].first == model_name(model));
  }
}

TEST_CASE("perceptual: the same bits on any thread count and up z turns it") {
  const Mesh m = make_bumpy_sphere(3);
  const SaliencyResult one = compute_saliency(m, model_options(Model::Perceptual, 1));
  CHECK(one.saliency == compute_saliency(m, model_options(Model::Perceptual, 3)).saliency);
  SaliencyOptions z = model_options(Model::Perceptual);
  z.up = UpAxis::Z;
  CHECK(compute_saliency(m, z).saliency != one.saliency);
}

TEST_CASE("perceptual: the fast method stays close to the exact") {
  const Mesh m = make_bumpy_sphere(4);
  SaliencyOptions fast = model_options(Model::Perceptual);
  fast.method = Method::Fast;
  const SaliencyResult e = compute_saliency(m, model_options(Model::Perceptual));
  const SaliencyResult f = compute_saliency(m, fast);
  CHECK(f.method == Method::Fast);
  CHECK(e.method == Method::Exact);
  double se = 0, sf = 0, see = 0, sff = 0, sef = 0;
  const double n = double(m.vertex_count());
  for (size_t i = 0; i < m.vertex_count(); ++i) se += e.saliency[i], sf += f.saliency[i];
  for (size_t i = 0; i < m.vertex_count(); ++i) {
    const double a = e.saliency[i] - se / n, b = f.saliency[i] - sf / n;
    see += a * a, sff += b * b, sef += a * b;
  }
  CHECK(sef / std::sqrt(see * sff) > 0.999);
}

TEST_CASE("the models other than the paper's refuse tiles and say what they need") {
  const Mesh m = make_sphere(1.0, 2);
  SaliencyOptions o = model_options(Model::Perceptual);
  o.tiles = 4;
  CHECK_THROWS_WITH(compute_saliency(m, o), Catch::Contains("model perceptual runs in memory, in one piece"));
  o.tiles = 0;
  o.scales = {60};
  CHECK_THROWS_WITH(compute_saliency(m, o), Catch::Contains("twice the scales"));
  CHECK(parse_model("center") == Model::Centre);
  CHECK_THROWS_WITH(parse_model("itti"), Catch::Contains("model must be lee2005, perceptual"));
  Request r;
  r.input = "in.ply";
  r.saliency_output = "out.ply";
  r.saliency.model = Model::Exposure;
  r.out_of_core.memory_limit = 700u << 20;
  CHECK_THROWS_WITH(check_request(r), Catch::Contains("--model exposure computes S in memory"));
}
