// The perceptual model through compute_saliency (api/perceptual_model.cpp): its known
// answers (a protrusion near the top outranks the same near the bottom, a sphere hidden
// inside another gets nothing), the cues alone equal to their functions, the same bits on
// any thread count, the fast method close to the exact, and what it refuses.
#include <algorithm>
#include <cmath>

#include "cli/synthetic.h"
#include "core/mesh_points.h"
#include "meshsal/meshsal.h"
#include "saliency/curvature.h"
#include "saliency/gaussian_filter.h"
#include "saliency/perceptual_cues.h"
#include "view/camera.h"
#include "view/exposure.h"
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
  const char* names[] = {"exposure_centre", "height", "rarity", "coarse"};
  for (size_t k = 0; k < 4; ++k) {
    CHECK(s.cues[k].first == names[k]);
    CHECK(s.cues[k].second.size() == both.vertex_count());
  }
}

namespace {

// exposure_cpu over the model's views and z-buffers, scaled to a maximum of 1.
std::vector<double> scaled_exposure(const Mesh& m, ExposureWeighting w, UpAxis up = UpAxis::Y) {
  VisibilityOptions v;
  v.resolution = kExposureResolution;
  std::vector<double> e = exposure_cpu(m, exposure_normals(m), frame_mesh(m, up), exposure_views(), w, v);
  scale_to_max(e, referenced_vertices(m));
  return e;
}

}  // namespace

TEST_CASE("perceptual: S is the smoothed product of its cues") {
  const Mesh m = make_bumpy_sphere(3);
  const std::vector<uint8_t> is_point = referenced_vertices(m);
  const SaliencyResult s = compute_saliency(m, model_options(Model::Perceptual));
  REQUIRE(s.cues.size() == 4);
  const std::vector<double>& x = s.cues[0].second;
  const std::vector<double>& h = s.cues[1].second;
  const std::vector<double>& r = s.cues[2].second;
  const std::vector<double>& c = s.cues[3].second;
  // The exposure through the centre bias, as exposure_cpu makes it.
  CHECK(x == scaled_exposure(m, {true, true}));
  std::vector<double> p(m.vertex_count(), 0.0);
  for (size_t i = 0; i < p.size(); ++i)
    if (is_point[i]) p[i] = x[i] * (1 + h[i] + r[i] + c[i]);
  const double diagonal = mesh_points_bbox(m, is_point).diagonal();
  std::vector<double> expect = gaussian_filter(m, is_point, p, {kFixationSigmaFrac * diagonal})[0];
  scale_to_max(expect, is_point);
  CHECK(s.saliency == expect);
}

TEST_CASE("perceptual: the winding of the faces does not matter") {
  const Mesh m = make_bumpy_sphere(3);
  Mesh turned = m;
  for (size_t t = 0; t < turned.triangle_count(); ++t) std::swap(turned.triangles[3 * t + 1], turned.triangles[3 * t + 2]);
  // Exposure alone: the same bits (|n.d| of an exactly negated normal).
  CHECK(compute_saliency(m, model_options(Model::Exposure)).saliency ==
        compute_saliency(turned, model_options(Model::Exposure)).saliency);
  // The whole model: the rarity's bins of a negated curvature may split a tie the other way.
  const std::vector<double> a = compute_saliency(m, model_options(Model::Perceptual)).saliency;
  const std::vector<double> b = compute_saliency(turned, model_options(Model::Perceptual)).saliency;
  double worst = 0;
  for (size_t i = 0; i < a.size(); ++i) worst = std::max(worst, std::fabs(a[i] - b[i]));
  CHECK(worst < 0.02);
  // An open sheet seen from above scores the same wound up or down.
  Mesh sheet = make_plane(2.0, 8);
  for (size_t i = 0; i < sheet.vertex_count(); ++i) std::swap(sheet.positions[3 * i + 1], sheet.positions[3 * i + 2]);
  Mesh down = sheet;
  for (size_t t = 0; t < down.triangle_count(); ++t) std::swap(down.triangles[3 * t + 1], down.triangles[3 * t + 2]);
  const SaliencyResult up_s = compute_saliency(sheet, model_options(Model::Exposure));
  CHECK(*std::max_element(up_s.saliency.begin(), up_s.saliency.end()) == 1.0);
  CHECK(up_s.saliency == compute_saliency(down, model_options(Model::Exposure)).saliency);
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
  // Exposure and centre: exposure_cpu with the one factor each; rarity from the Morton curvature.
  CHECK(compute_saliency(m, model_options(Model::Exposure)).saliency == scaled_exposure(m, {true, false}));
  CHECK(compute_saliency(m, model_options(Model::Centre)).saliency == scaled_exposure(m, {false, true}));
  SaliencyOptions turned = model_options(Model::Centre);
  turned.up = UpAxis::X;
  CHECK(compute_saliency(m, turned).saliency == scaled_exposure(m, {false, true}, UpAxis::X));
  {
    const double eps = scale_unit(m, is_point, 0.003);
    std::vector<double> sigmas;
    for (double k : rarity_descriptor_scales()) sigmas.push_back(k * eps);
    const std::vector<double> hc = mean_curvature_morton(m, mesh_points_bbox(m, is_point));
    std::vector<double> rarity = global_rarity(gaussian_filter(m, is_point, hc, sigmas), is_point);
    scale_to_max(rarity, is_point);
    CHECK(compute_saliency(m, model_options(Model::Rarity)).saliency == rarity);
  }
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
  r.out_of_core.memory_limit = 0;
  r.saliency_from = "s.ply";
  CHECK_THROWS_WITH(check_request(r), Catch::Contains("not with --saliency-from"));
  // The library's out-of-core entry points take the paper's model only.
  SaliencyOptions ooc;
  ooc.model = Model::Perceptual;
  OutOfCoreOptions limit;
  limit.memory_limit = 700u << 20;
  CHECK_THROWS_WITH(saliency_file("in.ply", "out.ply", ooc, limit), Catch::Contains("takes the paper's model only"));
}
