// The weightings of saliency-guided simplification beyond the paper's threshold: the curves,
// the balanced preset, `simplify --weights`, and `bench --simplify` (its JSON and its plot).
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>

#include "cli/synthetic.h"
#include "json_check.h"
#include "meshsal/meshsal.h"
#include "simplify/saliency_weights.h"
#include "cli_run.h"
#include "test_simplify_attributes_util.h"
#include "test_util.h"
#include "view/tradeoff_plot.h"

namespace fs = std::filesystem;
using namespace meshsal;

using meshsal_test::CliRun;
using meshsal_test::read_file;
using meshsal_test::scratch_dir;
using meshsal_test::run_cli;

TEST_CASE("weights: the three curves on known values", "[simplify]") {
  const std::vector<double> sm{0, 1, 2, 3, 4, 5, 6, 7, 8, 9};
  const std::vector<uint8_t> all(sm.size(), 1);

  // Rank step (gamma 0): 1 + lambda on the ranks >= 0.7, i.e. k / 9 >= 0.7: k = 7, 8, 9.
  SaliencyWeightOptions o;
  o.curve = WeightCurve::Rank;
  o.alpha_percentile = 70;
  o.gamma = 0;
  o.lambda = 2;
  SaliencyWeights sw = saliency_weights(sm, all, o);
  std::vector<double> w = sw.weights;
  CHECK(sw.alpha == Approx(6.3));
  for (int k = 0; k < 10; ++k) CHECK(w[k] == (k >= 7 ? 3.0 : 1.0));

  // Rank ramp (gamma 1) from the 50th: 1 + lambda (r - 0.5) / 0.5.
  o.alpha_percentile = 50;
  o.gamma = 1;
  o.lambda = 4;
  w = saliency_weights(sm, all, o).weights;
  CHECK(w[4] == 1.0);
  CHECK(w[5] == Approx(1 + 4 * (5.0 / 9 - 0.5) / 0.5));
  CHECK(w[9] == Approx(5.0));

  // Continuous: 1 + lambda min(cap, (Sm / alpha)^gamma), alpha = the 50th percentile = 4.5.
  o.curve = WeightCurve::Continuous;
  o.gamma = 2;
  o.lambda = 1;
  o.cap = 3;
  sw = saliency_weights(sm, all, o);
  w = sw.weights;
  CHECK(sw.alpha == Approx(4.5));
  CHECK(w[0] == 1.0);
  CHECK(w[3] == Approx(1 + (3 / 4.5) * (3 / 4.5)));
  CHECK(w[7] == Approx(1 + (7 / 4.5) * (7 / 4.5)));  // 2.42, under the cap
  CHECK(w[9] == Approx(4.0));                        // (9 / 4.5)^2 = 4, capped at 3

  // Vertices that are not mesh points get 0, whatever the curve.
  std::vector<uint8_t> mask = all;
  mask[9] = 0;
  w = saliency_weights(sm, mask, weight_preset(Weighting::Balanced)).weights;
  CHECK(w[9] == 0.0);

  o.gamma = 17;
  CHECK_THROWS_WITH(saliency_weights(sm, all, o).weights, "gamma must be a finite number in [0, 16]");
  o.gamma = 1;
  o.cap = -1;
  CHECK_THROWS_WITH(saliency_weights(sm, all, o).weights, "cap must be a finite number in [0, 1e+06]");
}

TEST_CASE("weights: the named presets", "[simplify]") {
  CHECK(parse_weighting("none") == Weighting::None);
  CHECK(parse_weighting("saliency") == Weighting::Saliency);
  CHECK(parse_weighting("balanced") == Weighting::Balanced);
  CHECK_THROWS_WITH(parse_weighting("Balanced"),
                    "weights must be 'saliency', 'balanced' or 'none', got 'Balanced'");
  const SaliencyWeightOptions paper = weight_preset(Weighting::Saliency);
  CHECK(paper.curve == WeightCurve::Threshold);
  CHECK(paper.lambda == 100);
  CHECK(paper.alpha_percentile == 30);
  CHECK(paper.floor == kDefaultWeightFloor);
  CHECK(kDefaultWeightFloor == 0.001);
  const SaliencyWeightOptions b = weight_preset(Weighting::Balanced);
  CHECK(b.curve == WeightCurve::Threshold);
  CHECK(b.alpha_percentile == 50);
  CHECK(b.lambda == 3);
  CHECK(b.floor == kDefaultWeightFloor);
}

TEST_CASE("weights: the balanced preset on the bumpy sphere", "[simplify]") {
  std::vector<uint8_t> feature;
  const Mesh mesh = make_bumpy_sphere(4, &feature);
  SaliencyOptions so;
  so.backend = Backend::Cpu;
  const SimplificationWeights sw = simplification_weights(mesh, weight_preset(Weighting::Balanced), so);
  const std::vector<double>& w = sw.weights;
  const double alpha = sw.alpha;
  SaliencyOptions so2 = so;
  so2.smoothed = true;
  const SaliencyResult s = compute_saliency(mesh, so2);
  CHECK(alpha == Approx(meshsal::percentile(s.smoothed, s.is_point, 50)));
  // W = 3 Sm on the top half of Sm, Sm below it.
  size_t n = 0, high = 0, feature_high = 0, feature_n = 0;
  for (size_t v = 0; v < w.size(); ++v) {
    if (!s.is_point[v]) continue;
    ++n;
    const bool amplified = s.smoothed[v] >= alpha;
    CHECK(w[v] == Approx(amplified ? 3 * s.smoothed[v] : s.smoothed[v]));
    high += amplified;
    if (feature[v]) ++feature_n, feature_high += amplified;
  }
  CHECK(n == mesh.vertex_count());
  CHECK(double(high) >= std::floor(0.5 * double(n)));
  CHECK(double(high) <= std::ceil(0.5 * double(n)) + 1);
  // The unique feature is the salient region: all of it is amplified, against half of the rest.
  REQUIRE(feature_n > 0);
  CHECK(feature_high == feature_n);
  CHECK(double(high - feature_high) <= 0.5 * double(n - feature_n));
}

TEST_CASE("weights: the result names the saliency's device, seams or not", "[simplify]") {
  SaliencyOptions so;
  so.backend = Backend::Cpu;
  const SaliencyWeightOptions wo = weight_preset(Weighting::Saliency);
  const Mesh plain = make_bumpy_sphere(3);
  CHECK(simplification_weights(plain, wo, so).device.rfind("cpu", 0) == 0);  // "cpu (N threads)"

  // Split at a UV seam: weighed on the position-welded mesh, the device still comes back.
  LoadOptions lo;
  lo.attributes = true;
  const Mesh seamed = load_mesh_bytes(attr_test::seamed_sphere_obj(make_sphere(1.0, 3)), "seamed.obj", lo);
  REQUIRE_FALSE(seamed.position_vertex.empty());
  const SimplificationWeights computed = simplification_weights(seamed, wo, so);
  CHECK(computed.device.rfind("cpu", 0) == 0);  // "cpu (N threads)"
  CHECK(computed.weights.size() == seamed.vertex_count());
  CHECK(computed.saliency.size() == seamed.vertex_count());

  // S given by the caller: no device computed it; the same weights come back.
  const SimplificationWeights given = simplification_weights(seamed, wo, so, computed.saliency);
  CHECK(given.device.empty());
  CHECK(given.weights == computed.weights);
}

TEST_CASE("cli simplify --json: the device of a seamed OBJ's saliency", "[simplify]") {
  const fs::path dir = scratch_dir("weights_seam_device");
  const std::string in = (dir / "seamed.obj").string(), out = (dir / "out.obj").string();
  {
    std::FILE* f = std::fopen(in.c_str(), "wb");
    REQUIRE(f);
    const std::string text = attr_test::seamed_sphere_obj(make_sphere(1.0, 3));
    std::fwrite(text.data(), 1, text.size(), f);
    std::fclose(f);
  }
  const CliRun r = run_cli("simplify '" + in + "' -o '" + out + "' --ratio 0.5 --backend cpu --json");
  INFO(r.err);
  REQUIRE(r.rc == 0);
  CHECK(meshsal_test::json_valid(r.out));
  CHECK(r.out.find("\"device\": \"cpu (") != std::string::npos);  // not "backend cpu"
  CHECK(r.out.find("backend") == std::string::npos);
  fs::remove_all(dir);
}

TEST_CASE("cli simplify --weights balanced and bad names", "[simplify]") {
  const fs::path dir = scratch_dir("weights");
  const std::string in = (dir / "bumpy.obj").string(), out = (dir / "out.obj").string();
  write_obj(in, make_bumpy_sphere(4));
  CliRun r = run_cli("simplify '" + in + "' -o '" + out + "' --ratio 0.2 --weights balanced --json");
  INFO(r.err);
  REQUIRE(r.rc == 0);
  CHECK(meshsal_test::json_valid(r.out));
  CHECK(r.out.find("\"weights\": \"balanced\"") != std::string::npos);
  CHECK(meshsal_test::json_number(r.out, "lambda") == 3);
  CHECK(meshsal_test::json_number(r.out, "alpha_percentile") == 50);
  // --lambda given: it overrides the preset's.
  r = run_cli("simplify '" + in + "' -o '" + out + "' --ratio 0.2 --weights balanced --lambda 5 --json");
  REQUIRE(r.rc == 0);
  CHECK(meshsal_test::json_number(r.out, "lambda") == 5);
  CHECK(meshsal_test::json_number(r.out, "alpha_percentile") == 50);
  // Balanced is the default (issue 22); the paper's recipe is one flag away.
  r = run_cli("simplify '" + in + "' -o '" + out + "' --ratio 0.2 --json");
  REQUIRE(r.rc == 0);
  CHECK(r.out.find("\"weights\": \"balanced\"") != std::string::npos);
  CHECK(meshsal_test::json_number(r.out, "lambda") == 3);
  CHECK(meshsal_test::json_number(r.out, "alpha_percentile") == 50);
  r = run_cli("simplify '" + in + "' -o '" + out + "' --ratio 0.2 --weights saliency --json");
  REQUIRE(r.rc == 0);
  CHECK(meshsal_test::json_number(r.out, "lambda") == 100);
  CHECK(meshsal_test::json_number(r.out, "alpha_percentile") == 30);

  r = run_cli("simplify '" + in + "' -o '" + out + "' --ratio 0.2 --weights heavy");
  CHECK(r.rc == 2);
  CHECK(r.err.find("--weights must be 'saliency', 'balanced' or 'none', got 'heavy'") != std::string::npos);
  r = run_cli("simplify '" + in + "' -o '" + out + "' --ratio 0.2 --weights none --saliency-from '" + in + "'");
  CHECK(r.rc == 2);
  CHECK(r.err.find("--saliency-from needs --weights saliency or balanced") != std::string::npos);
  fs::remove_all(dir);
}

TEST_CASE("tradeoff plot: axes, markers and legend", "[simplify]") {
  TradeoffPanel p;
  p.title = "model  1%";
  p.series[kSweepRank] = {{1.05, 0.9}, {1.2, 0.8}};
  p.series[kPaperRecipe] = {{2.5, 0.75}};
  p.series[kBalancedPreset] = {{1.1, 0.78}};
  p.series[kMeshoptimizer] = {{1.4, 1.3}};
  const Image img = tradeoff_plot({p, p}, {1.25, 0.8});
  REQUIRE(img.width == 2 * kPanelWidth);
  REQUIRE(img.height > kPanelHeight);
  // Pixels of one colour in a rectangle, and their mean x and y.
  auto find = [&](const uint8_t rgb[3], int x0, int y0, int x1, int y1, double* mx, double* my) {
    size_t n = 0;
    double sx = 0, sy = 0;
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x)
        if (std::equal(rgb, rgb + 3, img.at(x, y))) ++n, sx += x, sy += y;
    if (mx && n) *mx = sx / n;
    if (my && n) *my = sy / n;
    return n;
  };
  // The frame of the first panel: dark along the left axis.
  const int x0 = kPlotLeft, y0 = kPlotTop, y1 = kPanelHeight - kPlotBottom;
  for (int y = y0; y <= y1; y += 7) CHECK(img.at(x0, y)[0] < 60);
  // Tick values: dark text pixels left of the y axis and under the x axis.
  auto dark = [&](int xa, int ya, int xb, int yb) {
    size_t n = 0;
    for (int y = ya; y < yb; ++y)
      for (int x = xa; x < xb; ++x) n += img.at(x, y)[0] < 100 && img.at(x, y)[1] < 100;
    return n;
  };
  CHECK(dark(0, y0, x0 - 6, y1) > 50);
  CHECK(dark(x0, y1 + 6, kPanelWidth - kPlotRight, y1 + 20) > 50);
  // Each named marker inside the first panel, placed in the order of its values.
  uint8_t paper[3], balanced[3], meshopt[3], rank[3];
  tradeoff_series_colour(kPaperRecipe, paper);
  tradeoff_series_colour(kBalancedPreset, balanced);
  tradeoff_series_colour(kMeshoptimizer, meshopt);
  tradeoff_series_colour(kSweepRank, rank);
  double px = 0, py = 0, bx = 0, by = 0, mx = 0, my = 0;
  CHECK(find(paper, 0, 0, kPanelWidth, kPanelHeight, &px, &py) > 50);
  CHECK(find(balanced, 0, 0, kPanelWidth, kPanelHeight, &bx, &by) > 50);
  CHECK(find(meshopt, 0, 0, kPanelWidth, kPanelHeight, &mx, &my) > 50);
  CHECK(find(rank, 0, 0, kPanelWidth, kPanelHeight, nullptr, nullptr) > 10);
  CHECK(bx < mx);
  CHECK(mx < px);  // RMS 1.1 < 1.4 < 2.5: left to right
  CHECK(my < by);  // salient 1.3 above 0.78 (image y grows downwards)
  CHECK(by < py + 1);
  // The legend under the panels: a swatch of every series and text.
  const int legend_top = kPanelHeight;
  for (int s = 0; s < kTradeoffSeriesCount; ++s) {
    uint8_t c[3];
    tradeoff_series_colour(s, c);
    CHECK(find(c, 0, legend_top, img.width, img.height, nullptr, nullptr) > 10);
  }
  CHECK(dark(0, legend_top, img.width, img.height) > 500);
  CHECK_THROWS(tradeoff_plot({}, {1.25, 0.8}));
}

TEST_CASE("cli bench --simplify: the JSON tables and the plot", "[simplify]") {
  const fs::path dir = scratch_dir("weights");
  const std::string in = (dir / "bumpy.obj").string(), png = (dir / "tradeoff.png").string();
  write_obj(in, make_bumpy_sphere(5));
  CliRun r = run_cli("bench --simplify '" + in + "' --sweep none --repeat 1 --json --plot '" + png + "'");
  INFO(r.err);
  REQUIRE(r.rc == 0);
  CHECK(meshsal_test::json_valid(r.out));
  // runs: none, saliency, balanced (and meshopt) at 1% and 5%; tradeoff: all but none.
  const auto count = [&](const std::string& s) {
    size_t n = 0;
    for (size_t i = r.out.find(s); i != std::string::npos; i = r.out.find(s, i + 1)) ++n;
    return n;
  };
  CHECK(count("\"method\": \"none\"") == 2);
  CHECK(count("\"method\": \"balanced\"") == 4);  // in runs and in tradeoff, two ratios
  CHECK(count("\"method\": \"saliency\"") == 4);
  CHECK(count("\"curve\": \"threshold\"") == 4);  // saliency and balanced, two ratios
  CHECK(count("\"salient_rel\": ") >= 4);
  // The runs follow the other commands' keys: mesh, device, seconds, distances also in %.
  CHECK(count("\"device\": \"cpu\"") >= 8);
  const std::string run0 = r.out.substr(r.out.find("\"runs\""));
  CHECK(run0.find("\"mesh\": \"") != std::string::npos);
  const double diagonal = meshsal_test::json_number(run0, "diagonal");
  REQUIRE(diagonal > 0);
  for (const char* d : {"hausdorff", "rms", "salient_error"})
    CHECK(meshsal_test::json_number(run0, std::string(d) + "_percent") ==
          Approx(100 * meshsal_test::json_number(run0, d) / diagonal));
  const double sal = meshsal_test::json_number(r.out.substr(r.out.find("\"tradeoff\"")), "salient_rel");
  CHECK(sal > 0);
  CHECK(sal < 2);
  REQUIRE(fs::exists(png));
  CHECK(fs::file_size(png) > 2000);

  r = run_cli("bench --simplify '" + in + "' --sweep all");
  CHECK(r.rc == 2);
  r = run_cli("bench --simplify '" + in + "' --plot '" + (dir / "plot.txt").string() + "'");
  CHECK(r.rc == 1);
  CHECK(r.err.find(".png") != std::string::npos);
  fs::remove_all(dir);
}
