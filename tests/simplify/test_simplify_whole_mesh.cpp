// Issue 22 (2): the rule that a target at or above the face count returns the mesh as it
// is lives in the library (simplify_keeps_mesh, SimplifyReport::unchanged), so the CLI,
// batch and Python follow one rule: `batch --simplify 100000` on a small mesh failed the
// model; and smooth_saliency follows the method of the saliency it smooths.
#include <catch2/catch.hpp>

#include <atomic>
#include <filesystem>

#include "cli_run.h"
#include "cli/synthetic.h"
#include "meshsal/meshsal.h"
#include "test_batch_util.h"

using namespace meshsal;

TEST_CASE("simplify: a target at or above the face count returns the mesh as it is", "[simplify]") {
  const Mesh m = make_sphere(1.0, 2);  // 320 faces
  CHECK(simplify_keeps_mesh(SimplifyOptions{320, 0}, 320));
  CHECK_FALSE(simplify_keeps_mesh(SimplifyOptions{319, 0}, 320));
  SimplifyOptions ratio_one;
  ratio_one.ratio = 1;
  CHECK(simplify_keeps_mesh(ratio_one, 320));
  for (size_t target : {size_t(320), size_t(1000000)}) {
    SimplifyOptions opt;
    opt.target_faces = target;
    const Simplified s = simplify_mesh(m, opt);
    const Mesh& out = s.mesh;
    const SimplifyReport& rep = s.report;
    CHECK(out.positions == m.positions);
    CHECK(out.triangles == m.triangles);
    CHECK(rep.unchanged);
    CHECK(rep.reached);
    CHECK(rep.output_faces == 320);
    CHECK(rep.target_faces == 320);
    CHECK(rep.collapses == 0);
    CHECK(rep.vertex_origin.size() == m.vertex_count());
    CHECK(rep.note == "the target is at or above the mesh's 320 faces: the mesh is returned unchanged");
  }
  // With saliency weights no saliency is computed for it: a set cancel flag is never polled.
  std::atomic<bool> stop{true};
  SaliencyOptions so;
  so.backend = Backend::Cpu;
  so.cancel = &stop;
  SimplifyOptions opt;
  opt.target_faces = 500;
  Simplified s = simplify_with_saliency(m, opt, SaliencyWeightOptions{}, so);
  CHECK(s.mesh.triangles == m.triangles);
  CHECK(s.report.unchanged);
  // One face fewer is a simplification.
  opt.target_faces = 318;
  stop = false;
  s = simplify_with_saliency(m, opt, SaliencyWeightOptions{}, so);
  CHECK_FALSE(s.report.unchanged);
  CHECK(s.report.output_faces == 318);
}

TEST_CASE("batch --simplify with a face count above a model's writes it unchanged, exit 0", "[cli][batch]") {
  using namespace meshsal_test;
  const fs::path dir = scratch_dir("batch_whole_mesh");
  const std::string in = (dir / "small.obj").string();
  write_obj(in, make_sphere(1.0, 2));
  const CliRun r = run_cli("batch " + quoted(in) + " -o " + quoted((dir / "out").string()) + " --simplify 100000 -q", dir);
  CHECK(r.rc == 0);  // it used to fail the model
  CHECK(load_mesh((dir / "out" / "small_simplified.obj").string()).triangle_count() == 320);
  const std::string line = log_lines(dir / "out" / "batch.jsonl").at(0);
  CHECK(line.find("\"unchanged\": true") != std::string::npos);
  CHECK(json_text(line, "status") == "done");
}

TEST_CASE("smooth_saliency follows the method of the saliency it smooths", "[simplify][fast]") {
  const Mesh m = make_bumpy_sphere(3);
  for (Method method : {Method::Exact, Method::Fast}) {
    SaliencyOptions so;
    so.backend = Backend::Cpu;
    so.method = method;
    so.smoothed = true;
    const SaliencyResult r = compute_saliency(m, so);
    // Sm from a given S is the Sm compute_saliency makes with the same method, to the bit.
    CHECK(smooth_saliency(m, r.saliency, so) == r.smoothed);
  }
  // Dense enough that the fast method's cells hold several points (on a coarse mesh each
  // holds one, and the fast sums are the exact ones).
  const Mesh dense = make_bumpy_sphere(6);
  SaliencyOptions fast;
  fast.backend = Backend::Cpu;
  fast.method = Method::Fast;
  const std::vector<double> s = compute_saliency(dense, fast).saliency;
  CHECK(smooth_saliency(dense, s, fast) != smooth_saliency(dense, s, 0.003, 0));  // not the exact one
}
