// Issue 21 (2): saliency weights keep a positive floor, so no collapse is free. With the
// paper's literal rule a flat region has Sm = 0, W = 0, and simplification erased half of
// a plane with one bump while reporting "error 0%".
#include <catch2/catch.hpp>

#include <cmath>
#include <string>

#include "cli_run.h"
#include "cli/synthetic.h"
#include "meshsal/meshsal.h"
#include "test_util.h"

using namespace meshsal;

namespace {

// A unit plane with one bump: flat almost everywhere.
Mesh plane_with_bump() { return make_plane_with_bump(1.0, 60, 0.1, 0.06); }

struct Outcome {
  double hausdorff = 0;  // fraction of the diagonal
  double error = 0;      // the report's error, fraction of the diagonal
};

Outcome simplify_plane(const SaliencyWeightOptions& wo) {
  const Mesh m = plane_with_bump();
  SaliencyOptions so;
  so.backend = Backend::Cpu;
  SimplifyOptions opt;
  opt.ratio = 0.1;
  const Simplified out = simplify_with_saliency(m, opt, wo, so);
  const SurfaceComparison c = compare_surfaces(m, out.mesh, {});
  return {c.hausdorff / c.diagonal, out.report.error};
}

}  // namespace

TEST_CASE("weight floor: a plane with one bump keeps its area at 10% with every weighting", "[simplify]") {
  for (Weighting w : {Weighting::Saliency, Weighting::Balanced}) {
    const SaliencyWeightOptions wo = weight_preset(w);
    CHECK(wo.floor == kDefaultWeightFloor);
    const Outcome o = simplify_plane(wo);
    INFO("weighting " << int(w) << ": Hausdorff " << 100 * o.hausdorff << "% of the diagonal");
    CHECK(o.hausdorff < 0.01);  // the literal rule: over 10% (below)
    CHECK(o.error > 0);
  }
  // The literal rule (floor 0) cuts the flat part away; the error says so, not "0%".
  SaliencyWeightOptions literal = weight_preset(Weighting::Saliency);
  literal.floor = 0;
  const Outcome o = simplify_plane(literal);
  INFO("literal rule: Hausdorff " << 100 * o.hausdorff << "%, reported error " << 100 * o.error << "%");
  CHECK(o.hausdorff > 0.1);
  // It used to report 0. How much of the Hausdorff distance it reports depends on which of
  // the many free collapses went first (measured 24-25% of it, 8.2-8.6% of the diagonal):
  // it must report several % of the diagonal, where the floored weightings keep < 1%.
  CHECK(o.error > 0.05);
}

TEST_CASE("weight floor: saliency 0 everywhere gives plain quadrics, the literal rule 0", "[simplify]") {
  const std::vector<double> zero(5, 0.0);
  const std::vector<uint8_t> points{1, 1, 1, 1, 0};
  const std::vector<double> w = saliency_weights(zero, points, SaliencyWeightOptions{}).weights;
  CHECK(w == std::vector<double>{1, 1, 1, 1, 0});
  SaliencyWeightOptions literal;
  literal.floor = 0;
  CHECK(saliency_weights(zero, points, literal).weights == std::vector<double>(5, 0.0));
  // Otherwise the floor is a share of the mean: Sm {0, 1, 2} (alpha 0.6) gives W {0, 100, 200},
  // mean 100, floor 0.1.
  const std::vector<double> w2 = saliency_weights({0.0, 1.0, 2.0}, {1, 1, 1}, SaliencyWeightOptions{}).weights;
  CHECK(w2[0] == Approx(kDefaultWeightFloor * 100));
  CHECK(w2[1] == Approx(100.0));
  CHECK(w2[2] == Approx(200.0));
}

TEST_CASE("weight floor: the default leaves the paper's recipe on the bunny as it was", "[simplify]") {
  MESHSAL_REQUIRE_MESH(path, "bunny_36k.obj");
  const Mesh m = load_mesh(path);
  SaliencyOptions so;
  so.backend = Backend::Cpu;
  const std::vector<double> s = compute_saliency(m, so).saliency;
  SimplifyOptions opt;
  opt.ratio = 0.1;
  SaliencyWeightOptions literal;
  literal.floor = 0;
  // Measured (docs/method.md, "Weight floor"): a few vertices move, the distances stay to
  // 5 digits (Hausdorff, RMS and salient-region error).
  const Mesh a = simplify_with_saliency(m, opt, SaliencyWeightOptions{}, so, s).mesh;
  const Mesh b = simplify_with_saliency(m, opt, literal, so, s).mesh;
  CHECK(a.triangle_count() == b.triangle_count());
  const SurfaceComparison ca = compare_surfaces(m, a, s), cb = compare_surfaces(m, b, s);
  CHECK(ca.hausdorff == Approx(cb.hausdorff).epsilon(1e-4));
  CHECK(ca.rms == Approx(cb.rms).epsilon(1e-4));
  CHECK(ca.salient_error == Approx(cb.salient_error).epsilon(1e-4));
}

TEST_CASE("weight floor: simplify and batch --simplify keep the plane, --weight-floor 0 is the literal rule", "[cli][simplify]") {
  using namespace meshsal_test;
  const auto dir = scratch_dir("weight_floor");
  const std::string in = (dir / "plane.obj").string();
  write_obj(in, plane_with_bump());
  const auto hausdorff = [&](const std::string& out) {
    return compare_surfaces(load_mesh(in), load_mesh(out), {});
  };
  CliRun r = run_cli("simplify " + quoted(in) + " -o " + quoted((dir / "s.obj").string()) + " --ratio 0.1", dir);
  REQUIRE(r.rc == 0);
  CHECK(r.out.find("error      0%") == std::string::npos);
  SurfaceComparison c = hausdorff((dir / "s.obj").string());
  CHECK(c.hausdorff < 0.01 * c.diagonal);
  r = run_cli("simplify " + quoted(in) + " -o " + quoted((dir / "b.obj").string()) + " --ratio 0.1 --weights balanced", dir);
  REQUIRE(r.rc == 0);
  c = hausdorff((dir / "b.obj").string());
  CHECK(c.hausdorff < 0.01 * c.diagonal);
  r = run_cli("simplify " + quoted(in) + " -o " + quoted((dir / "l.obj").string()) +
                  " --ratio 0.1 --weight-floor 0 --json", dir);
  REQUIRE(r.rc == 0);
  c = hausdorff((dir / "l.obj").string());
  CHECK(c.hausdorff > 0.1 * c.diagonal);
  CHECK(r.out.find("\"error_percent\": 0,") == std::string::npos);
  CHECK(r.out.find("\"weight_floor\": 0,") != std::string::npos);
  r = run_cli("batch " + quoted(in) + " -o " + quoted((dir / "out").string()) + " --simplify 0.1 -q", dir);
  REQUIRE(r.rc == 0);
  c = hausdorff((dir / "out" / "plane_simplified.obj").string());
  CHECK(c.hausdorff < 0.01 * c.diagonal);
  r = run_cli("batch " + quoted(in) + " -o " + quoted((dir / "lit").string()) + " --simplify 0.1 --weight-floor 0 -q", dir);
  REQUIRE(r.rc == 0);
  c = hausdorff((dir / "lit" / "plane_simplified.obj").string());
  CHECK(c.hausdorff > 0.1 * c.diagonal);
}
