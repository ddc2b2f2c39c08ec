// --model from the command line: saliency's JSON and summary name it, --dump-scales keeps
// the cues, batch writes the bytes saliency writes, simplify and viewpoint take it, and a
// model that is not one is a usage error.
#include <catch2/catch.hpp>

#include <string>

#include "cli/synthetic.h"
#include "cli_run.h"
#include "json_check.h"
#include "meshsal/meshsal.h"
#include "test_io_util.h"

using meshsal_test::CliRun;
using meshsal_test::quoted;
using meshsal_test::run_cli;

TEST_CASE("cli --model perceptual: the library's S and its cues in the PLY and the model in the JSON", "[cli]") {
  meshsal_test::TempDir dir;
  const meshsal::Mesh m = meshsal::make_bumpy_sphere(3);
  const std::string in = dir.file("bumpy.ply"), out = dir.file("s.ply");
  meshsal::write_ply(in, m, {});
  const CliRun r = run_cli("saliency " + quoted(in) + " -o " + quoted(out) +
                               " --model perceptual --up z --dump-scales --backend cpu --json", dir.path);
  INFO(r.err);
  REQUIRE(r.rc == 0);
  REQUIRE(meshsal_test::json_valid(r.out));
  CHECK(r.out.find("\"model\": \"perceptual\"") != std::string::npos);
  const meshsal::LoadedMesh back = meshsal::read_mesh(out);
  for (const char* cue : {"cue_exposure_centre", "cue_height", "cue_rarity", "cue_coarse", "quality"})
    CHECK(back.properties.count(cue) == 1);
  meshsal::SaliencyOptions o;
  o.model = meshsal::Model::Perceptual;
  o.up = meshsal::UpAxis::Z;
  const meshsal::SaliencyResult lib = meshsal::compute_saliency(meshsal::load_mesh(in), o);
  const std::vector<float>& q = back.properties.at("quality");
  REQUIRE(q.size() == lib.saliency.size());
  for (size_t i = 0; i < q.size(); ++i) CHECK(q[i] == float(lib.saliency[i]));
  // Height rises along z: 0 at the lowest vertex, 1 at the highest.
  const std::vector<float>& h = back.properties.at("cue_height");
  size_t lo = 0, hi = 0;
  for (size_t i = 0; i < q.size(); ++i) {
    if (m.positions[3 * i + 2] < m.positions[3 * lo + 2]) lo = i;
    if (m.positions[3 * i + 2] > m.positions[3 * hi + 2]) hi = i;
  }
  CHECK(h[lo] == 0.0f);
  CHECK(h[hi] == 1.0f);
}

TEST_CASE("cli --model: batch writes the bytes saliency writes and simplify and viewpoint take it", "[cli]") {
  meshsal_test::TempDir dir;
  const std::string in = dir.file("ball.ply");
  meshsal::write_ply(in, meshsal::make_bumpy_sphere(3), {});
  REQUIRE(run_cli("saliency " + quoted(in) + " -o " + quoted(dir.file("s.ply")) + " --model perceptual -q", dir.path).rc == 0);
  const CliRun b = run_cli("batch " + quoted(in) + " -o " + quoted(dir.file("out")) + " --model perceptual -q", dir.path);
  INFO(b.err);
  REQUIRE(b.rc == 0);
  CHECK(meshsal_test::read_file(dir.file("s.ply")) == meshsal_test::read_file(dir.file("out/ball_saliency.ply")));
  CHECK(meshsal_test::read_file(dir.file("out/batch.jsonl")).find("\"model\": \"perceptual\"") != std::string::npos);
  // simplify and viewpoint: the model's S changes what they make.
  for (const char* model : {"lee2005", "perceptual"}) {
    const CliRun s = run_cli("simplify " + quoted(in) + " -o " + quoted(dir.file(std::string(model) + ".obj")) +
                                 " --ratio 0.3 -q --model " + model, dir.path);
    INFO(s.err);
    REQUIRE(s.rc == 0);
  }
  CHECK(meshsal_test::read_file(dir.file("lee2005.obj")) != meshsal_test::read_file(dir.file("perceptual.obj")));
  const CliRun v = run_cli("viewpoint " + quoted(in) + " --model height --restarts 2 --json", dir.path);
  const CliRun l = run_cli("viewpoint " + quoted(in) + " --restarts 2 --json", dir.path);
  INFO(v.err);
  REQUIRE(v.rc == 0);
  REQUIRE(l.rc == 0);
  CHECK(meshsal_test::json_number(v.out, "visible_score") != meshsal_test::json_number(l.out, "visible_score"));
  // A batch run again with another model computes again (its record names the model).
  const CliRun again = run_cli("batch " + quoted(in) + " -o " + quoted(dir.file("out")) + " --model height --json", dir.path);
  INFO(again.err);
  REQUIRE(again.rc == 0);
  CHECK(meshsal_test::json_number(again.out, "computed") == 1);
  CHECK(meshsal_test::read_file(dir.file("s.ply")) != meshsal_test::read_file(dir.file("out/ball_saliency.ply")));
}

TEST_CASE("cli --model: an unknown model is a usage error naming the models", "[cli]") {
  meshsal_test::TempDir dir;
  const std::string in = dir.file("ball.ply");
  meshsal::write_ply(in, meshsal::make_sphere(1.0, 2), {});
  const CliRun r = run_cli("saliency " + quoted(in) + " -o " + quoted(dir.file("s.ply")) + " --model itti", dir.path);
  CHECK(r.rc == 2);
  CHECK(r.err.find("--model") != std::string::npos);
  CHECK(r.err.find("perceptual") != std::string::npos);
  const CliRun t = run_cli("saliency " + quoted(in) + " -o " + quoted(dir.file("t.ply")) +
                               " --model perceptual --memory-limit 700M", dir.path);
  CHECK(t.rc == 2);
  CHECK(t.err.find("in memory, in one piece") != std::string::npos);
  const CliRun f = run_cli("simplify " + quoted(in) + " -o " + quoted(dir.file("f.obj")) + " --ratio 0.5 --saliency-from " +
                               quoted(in) + " --model height", dir.path);
  CHECK(f.rc == 2);
  CHECK(f.err.find("not with --saliency-from") != std::string::npos);
}
