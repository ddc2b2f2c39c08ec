// Issue 22 (item 3): meshsal batch run again over its own results: a log a killed run left
// with a torn last line, an input folder that is also the output folder, and the
// simplification options of `meshsal simplify` (--target-error, --lock-border, attributes).
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <set>
#include <string>

#include "cli_run.h"
#include "cli/synthetic.h"
#include "json_check.h"
#include "meshsal/meshsal.h"
#include "test_batch_util.h"
#include "test_simplify_attributes_util.h"

using namespace meshsal_test;
namespace fs = std::filesystem;

TEST_CASE("batch: a torn last line in the log is noted, and the new lines start on a line of their own",
          "[cli][batch]") {
  const fs::path dir = scratch_dir("batch_torn");
  fs::create_directories(dir / "in");
  meshsal::write_obj((dir / "in" / "a.obj").string(), meshsal::make_sphere(1.0, 1));
  const fs::path out = dir / "out", log = out / "batch.jsonl";
  const std::string args = "batch " + quoted((dir / "in").string()) + " -o " + quoted(out.string()) + " --backend cpu";
  CliRun r = run_cli(args, dir, 120);
  REQUIRE(r.rc == 0);
  CHECK(r.err.find("torn") == std::string::npos);
  REQUIRE(log_lines(log).size() == 1);

  // A run killed part way through its line: no newline at the end.
  const std::string torn = "{\"mesh\": \"" + (dir / "in" / "a.obj").string() + "\", \"status\": \"do";
  std::ofstream(log, std::ios::app | std::ios::binary) << torn;
  r = run_cli(args + " --force", dir, 120);
  CHECK(r.rc == 0);
  CHECK(r.err == "note: " + log.string() + ": ignored a torn last line (" + std::to_string(torn.size()) +
                     " bytes) from an interrupted run\n");
  std::vector<std::string> lines = log_lines(log);
  REQUIRE(lines.size() == 3);
  CHECK(json_valid(lines[0]));
  CHECK(lines[1] == torn);  // left as it was: the log is only ever appended to
  CHECK(json_valid(lines[2]));
  CHECK(json_text(lines[2], "status") == "done");

  // A last line that is not JSON although it ends with a newline; blank lines after it.
  const std::string junk = "\"status\": \"done\", \"na";
  std::ofstream(log, std::ios::app | std::ios::binary) << junk << "\n\n";
  r = run_cli(args, dir, 120);
  CHECK(r.rc == 0);
  CHECK(r.err.find("ignored a torn last line (" + std::to_string(junk.size()) + " bytes)") != std::string::npos);
  lines = log_lines(log);
  REQUIRE(lines.size() == 6);
  CHECK(lines[3] == junk);
  CHECK(json_text(lines[5], "status") == "skipped");
  CHECK(json_valid(lines[5]));

  // A whole last line missing only its newline is a record, not torn: completed silently.
  std::string text = read_text(log);
  text.pop_back();
  std::ofstream(log, std::ios::trunc | std::ios::binary) << text;
  r = run_cli(args, dir, 120);
  CHECK(r.rc == 0);
  CHECK(r.err.find("torn") == std::string::npos);
  lines = log_lines(log);
  REQUIRE(lines.size() == 7);
  for (size_t i : {5, 6}) CHECK(json_valid(lines[i]));
}

TEST_CASE("batch: the input folder may be the output folder, and what batch wrote there is never an input",
          "[cli][batch]") {
  const fs::path dir = scratch_dir("batch_in_out");
  const fs::path models = dir / "models";
  fs::create_directories(models);
  meshsal::write_obj((models / "a.obj").string(), meshsal::make_sphere(1.0, 2));
  meshsal::write_ply((models / "b.ply").string(), meshsal::make_bumpy_sphere(2), {});
  const std::string base = "batch " + quoted(models.string()) + " -o " + quoted(models.string()) +
                           " --backend cpu --size 64 --resolution 32 --restarts 1 --contact-sheet " +
                           quoted((models / "sheet.png").string());
  const std::string args = base + " --simplify 0.5";
  const auto meshes_logged = [&] {
    std::set<std::string> meshes;
    for (const std::string& line : log_lines(models / "batch.jsonl")) meshes.insert(json_text(line, "mesh"));
    return meshes;
  };
  const std::set<std::string> two = {(models / "a.obj").string(), (models / "b.ply").string()};
  CliRun r = run_cli(args, dir, 240);
  INFO(r.err);
  CHECK(r.rc == 0);
  CHECK(r.out.find("batch: 2 models: 2 computed, 0 skipped, 0 failed") != std::string::npos);
  for (const char* f : {"a_saliency.ply", "a_simplified.obj", "a_view.png", "b_saliency.ply", "b_simplified.obj",
                        "b_view.png", "sheet.png", "batch.jsonl"})
    CHECK(fs::exists(models / f));
  // Again: the same two models, up to date; none of the outputs taken as a model.
  r = run_cli(args, dir, 240);
  CHECK(r.rc == 0);
  CHECK(r.out.find("batch: 2 models: 0 computed, 2 skipped, 0 failed") != std::string::npos);
  CHECK(r.err.empty());
  CHECK(meshes_logged() == two);
  CHECK_FALSE(fs::exists(models / "a_saliency_saliency.ply"));
  // Without --simplify its simplified meshes are still outputs, not models (the options
  // changed: both computed again).
  r = run_cli(base, dir, 240);
  CHECK(r.rc == 0);
  CHECK(r.out.find("batch: 2 models: 2 computed, 0 skipped, 0 failed") != std::string::npos);
  CHECK(meshes_logged() == two);
  // A run stopped while making a's outputs left its state file as started: they are still
  // outputs, and a is computed again.
  std::ofstream(models / ".meshsal-batch" / "a.state", std::ios::trunc) << "meshsal-batch-state 1\nstarted\n";
  r = run_cli(base, dir, 240);
  CHECK(r.rc == 0);
  CHECK(r.out.find("batch: 2 models: 1 computed, 1 skipped, 0 failed") != std::string::npos);
  CHECK(meshes_logged() == two);
  // A mesh of the user's with an output's name but no model of that name is a model.
  meshsal::write_obj((models / "c_simplified.obj").string(), meshsal::make_sphere(1.0, 1));
  r = run_cli(base, dir, 240);
  CHECK(r.rc == 0);
  CHECK(r.out.find("batch: 3 models: 1 computed, 2 skipped, 0 failed") != std::string::npos);
}

TEST_CASE("batch: the simplified mesh is simplify's byte for byte, attributes, --target-error and --lock-border "
          "included", "[cli][batch]") {
  const fs::path dir = scratch_dir("batch_simplify_same");
  const fs::path in = dir / "in";
  fs::create_directories(in);
  // A textured sphere (vt with a UV seam, vn), a plain bumpy sphere, a plane with a border.
  std::ofstream(in / "tex.obj") << attr_test::seamed_sphere_obj(meshsal::make_sphere(1.0, 3));
  meshsal::write_obj((in / "plain.obj").string(), meshsal::make_bumpy_sphere(3));
  meshsal::write_ply((in / "plane.ply").string(), meshsal::make_plane_with_bump(2.0, 16, 0.3, 0.3), {});
  const std::string common = " --backend cpu";
  struct Case {
    const char *batch, *simplify;
  };
  const Case cases[] = {{"--simplify 0.5 --weights saliency", "--ratio 0.5 --weights saliency"},
                        {"--simplify 200 --target-error 0.5 --lock-border --weights saliency",
                         "--target-faces 200 --target-error 0.5 --lock-border --weights saliency"},
                        {"--target-error 1 --weights balanced", "--target-error 1 --weights balanced"},
                        {"--simplify 0.3 --weights none", "--ratio 0.3 --weights none"}};
  int k = 0;
  for (const Case& c : cases) {
    ++k;
    INFO(c.batch);
    const fs::path out = dir / ("out" + std::to_string(k));
    CliRun r = run_cli("batch " + quoted(in.string()) + " -o " + quoted(out.string()) + " " + c.batch + common, dir, 240);
    INFO(r.err);
    REQUIRE(r.rc == 0);
    for (const char* name : {"tex", "plain", "plane"}) {
      INFO(name);
      const std::string ext = std::string(name) == "plane" ? ".ply" : ".obj";
      const fs::path mine = dir / (std::string(name) + "_" + std::to_string(k) + ".obj");
      r = run_cli("simplify " + quoted((in / (name + ext)).string()) + " -o " + quoted(mine.string()) + " " +
                      c.simplify + common + " -q",
                  dir, 240);
      REQUIRE(r.rc == 0);
      const std::string batch_file = read_text(out / (std::string(name) + "_simplified.obj"));
      CHECK(!batch_file.empty());
      CHECK(batch_file == read_text(mine));
      if (std::string(name) == "tex") {
        CHECK(batch_file.find("\nvt ") != std::string::npos);
        CHECK(batch_file.find("\nvn ") != std::string::npos);
      }
    }
  }
  // The options are in the state: a change computes the models again.
  const std::string args = "batch " + quoted((in / "tex.obj").string()) + " -o " + quoted((dir / "out1").string()) +
                           " --simplify 0.5 --weights saliency" + common;
  CliRun r = run_cli(args, dir, 240);
  CHECK(r.out.find("1 models: 0 computed, 1 skipped") != std::string::npos);
  r = run_cli(args + " --target-error 0.5", dir, 240);
  CHECK(r.out.find("1 models: 1 computed, 0 skipped") != std::string::npos);
  CHECK(json_number(log_lines(dir / "out1" / "batch.jsonl").back(), "target_error_percent") == 0.5);
  r = run_cli(args + " --target-error 0.5", dir, 240);
  CHECK(r.out.find("1 models: 0 computed, 1 skipped") != std::string::npos);
  r = run_cli(args + " --target-error 0.5 --lock-border", dir, 240);
  CHECK(r.out.find("1 models: 1 computed, 0 skipped") != std::string::npos);
  // --lock-border alone simplifies nothing.
  r = run_cli("batch " + quoted(in.string()) + " -o " + quoted((dir / "out9").string()) + " --lock-border", dir, 60);
  CHECK(r.rc == 2);
  CHECK(r.err.find("--lock-border needs --simplify, --target-error or --lod") != std::string::npos);
}
