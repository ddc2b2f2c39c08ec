// `meshsal batch` end to end on the CPU path: the log, failures, resuming, inputs.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>

#include "json_check.h"
#include "saliency/saliency.h"
#include "test_batch_util.h"
#include "test_util.h"

using namespace meshsal;
using namespace meshsal_test;

namespace {

// The statistics `saliency --json` prints, from the library, for comparison.
double max_saliency(const Mesh& mesh) {
  const SaliencyResult r = compute_saliency_cpu(mesh, {});
  double mx = 0;
  for (size_t v = 0; v < r.saliency.size(); ++v)
    if (r.is_point[v]) mx = std::max(mx, r.saliency[v]);
  return mx;
}

// The latest line of the log for `file` (runs append theirs after the earlier runs').
const std::string* line_for(const std::vector<std::string>& lines, const std::string& file) {
  for (auto it = lines.rbegin(); it != lines.rend(); ++it) {
    const std::string mesh = json_text(*it, "mesh");
    if (mesh.size() >= file.size() && mesh.compare(mesh.size() - file.size(), file.size(), file) == 0) return &*it;
  }
  return nullptr;
}

}  // namespace

TEST_CASE("batch: one JSON line per model, the broken one with its error, exit 1", "[batch]") {
  const fs::path dir = batch_scratch("log");
  const fs::path in = make_batch_inputs(dir), out = dir / "out";
  const BatchRun r = run_meshsal("batch " + in.string() + " -o " + out.string() + " --backend cpu", dir);
  INFO(r.err);
  CHECK(r.exit_code == 1);  // one model failed, the others went on
  CHECK(r.out.find("batch: 4 models: 3 computed, 0 skipped, 1 failed") != std::string::npos);
  CHECK(r.err == "error: " + (in / "broken.obj").string() + ": line 3: face index 7 is beyond the file's 2 vertices (OBJ indices start at 1)\n");

  const std::vector<std::string> lines = log_lines(out / "batch.jsonl");
  REQUIRE(lines.size() == 4);
  for (const std::string& l : lines) CHECK(json_valid(l));
  // Inputs in name order.
  CHECK(json_text(lines[0], "mesh") == (in / "ball.obj").string());
  CHECK(json_text(lines[1], "mesh") == (in / "broken.obj").string());
  CHECK(json_text(lines[2], "mesh") == (in / "bumpy.ply").string());
  CHECK(json_text(lines[3], "mesh") == (in / "cube.off").string());
  CHECK(json_text(lines[1], "status") == "failed");
  CHECK(json_text(lines[1], "error") == (in / "broken.obj").string() + ": line 3: face index 7 is beyond the file's 2 vertices (OBJ indices start at 1)");

  for (const char* name : {"ball.obj", "bumpy.ply", "cube.off"}) {
    INFO(name);
    const std::string& l = *line_for(lines, name);
    CHECK(json_text(l, "status") == "done");
    const Mesh mesh = load_mesh((in / name).string());
    CHECK(json_number(l, "vertices") == double(mesh.vertex_count()));
    CHECK(json_number(l, "faces") == double(mesh.triangle_count()));
    CHECK(json_text(l, "device").rfind("cpu (", 0) == 0);
    CHECK(json_number(l, "max") == Approx(max_saliency(mesh)).epsilon(1e-7));
    CHECK(json_number(l, "gaussian_sweep") >= 0);
    CHECK(json_number(l, "read_seconds") >= 0);
    // The PLY holds the library's saliency of this mesh.
    const std::string ply = json_text(l, "output");
    const std::string stem = std::string(name).substr(0, std::string(name).find('.'));
    CHECK(ply == (out / (stem + "_saliency.ply")).string());
    const std::vector<double> s = load_saliency_ply(ply, mesh);
    const SaliencyResult expected = compute_saliency_cpu(mesh, {});
    REQUIRE(s.size() == expected.saliency.size());
    for (size_t v = 0; v < s.size(); ++v) CHECK(s[v] == Approx(expected.saliency[v]).margin(1e-6));
  }
  CHECK_FALSE(fs::exists(out / "broken_saliency.ply"));
}

TEST_CASE("batch: a second run skips every model, --force and a newer input redo them", "[batch]") {
  const fs::path dir = batch_scratch("resume");
  const fs::path in = make_batch_inputs(dir), out = dir / "out";
  const std::string args = "batch " + in.string() + " -o " + out.string() + " --backend cpu --simplify 0.5";
  REQUIRE(run_meshsal(args, dir).exit_code == 1);
  const fs::path ply = out / "ball_saliency.ply", obj = out / "ball_simplified.obj";
  REQUIRE(fs::exists(obj));
  const long long first = mtime_ns(ply);

  BatchRun again = run_meshsal(args, dir);
  CHECK(again.exit_code == 1);  // broken.obj fails again: it has no outputs
  CHECK(again.out.find("0 computed, 3 skipped, 1 failed") != std::string::npos);
  std::vector<std::string> lines = log_lines(out / "batch.jsonl");
  REQUIRE(lines.size() == 8);  // the first run's 4 lines, then this run's
  for (const char* name : {"ball.obj", "bumpy.ply", "cube.off"}) {
    INFO(name);
    CHECK(json_text(*line_for(lines, name), "status") == "skipped");
    CHECK(line_for(lines, name)->find("\"vertices\": ") != std::string::npos);  // with its numbers
  }
  CHECK(json_text(*line_for(lines, "broken.obj"), "status") == "failed");
  CHECK(mtime_ns(ply) == first);

  // A model without one of its outputs is redone; asking for more outputs redoes all.
  fs::remove(obj);
  again = run_meshsal(args, dir);
  CHECK(again.out.find("1 computed, 2 skipped, 1 failed") != std::string::npos);
  CHECK(json_text(*line_for(log_lines(out / "batch.jsonl"), "ball.obj"), "status") == "done");
  CHECK(fs::exists(obj));

  // An input modified after its outputs.
  fs::last_write_time(in / "cube.off", fs::file_time_type::clock::now() + std::chrono::seconds(5));
  again = run_meshsal(args, dir);
  CHECK(again.out.find("1 computed, 2 skipped, 1 failed") != std::string::npos);
  CHECK(json_text(*line_for(log_lines(out / "batch.jsonl"), "cube.off"), "status") == "done");

  again = run_meshsal(args + " --force", dir);
  CHECK(again.out.find("3 computed, 0 skipped, 1 failed") != std::string::npos);
  lines = log_lines(out / "batch.jsonl");
  for (const char* name : {"ball.obj", "bumpy.ply", "cube.off"}) CHECK(json_text(*line_for(lines, name), "status") == "done");
  CHECK(mtime_ns(ply) > first);
}

TEST_CASE("batch: a glob and a list file", "[batch]") {
  const fs::path dir = batch_scratch("glob");
  const fs::path in = make_batch_inputs(dir), out = dir / "out";
  BatchRun r = run_meshsal("batch '" + (in / "b*").string() + "' -o " + out.string() + " --backend cpu -q", dir);
  CHECK(r.exit_code == 1);
  CHECK(r.out.empty());  // -q
  std::vector<std::string> lines = log_lines(out / "batch.jsonl");
  REQUIRE(lines.size() == 3);  // ball.obj, broken.obj, bumpy.ply
  CHECK(json_text(lines[0], "mesh") == (in / "ball.obj").string());
  CHECK(json_text(lines[2], "mesh") == (in / "bumpy.ply").string());

  // Relative items from the list's folder, a comment, a blank line, a repeat (kept once).
  std::ofstream(dir / "list.txt") << "# two models\nin/cube.off\n\n" << (in / "ball.obj").string() << "\nin/cube.off\n";
  const fs::path out2 = dir / "out2";
  r = run_meshsal("batch --list " + (dir / "list.txt").string() + " -o " + out2.string() + " --backend cpu --log " +
                      (dir / "list.jsonl").string(), dir);
  INFO(r.err);
  CHECK(r.exit_code == 0);
  lines = log_lines(dir / "list.jsonl");
  REQUIRE(lines.size() == 2);
  CHECK(json_text(lines[0], "mesh") == (dir / "in/cube.off").string());
  CHECK(json_text(lines[1], "mesh") == (in / "ball.obj").string());
  CHECK(fs::exists(out2 / "cube_saliency.ply"));
  CHECK_FALSE(fs::exists(out2 / "batch.jsonl"));

  // The same through @LIST.
  r = run_meshsal("batch @" + (dir / "list.txt").string() + " -o " + (dir / "out3").string() + " --backend cpu -q", dir);
  CHECK(r.exit_code == 0);
  CHECK(log_lines(dir / "out3" / "batch.jsonl").size() == 2);
}

TEST_CASE("batch: bad options and inputs are refused before any work", "[batch]") {
  const fs::path dir = batch_scratch("usage");
  const fs::path in = make_batch_inputs(dir), out = dir / "out";
  BatchRun r = run_meshsal("batch -o " + out.string(), dir);
  CHECK(r.exit_code == 2);
  CHECK(r.err == "error: give the models: files, folders, globs, @LIST or --list FILE (see --help)\n");
  r = run_meshsal("batch " + in.string() + " -o " + out.string() + " --simplify 2.5", dir);
  CHECK(r.exit_code == 2);
  CHECK(r.err.find("--simplify: a value above 1 is a face count and must be a whole number") != std::string::npos);
  r = run_meshsal("batch " + in.string() + " -o " + out.string() + " --simplify 0", dir);
  CHECK(r.exit_code == 2);
  r = run_meshsal("batch '" + (in / "*.stl").string() + "' -o " + out.string(), dir);
  CHECK(r.exit_code == 1);
  CHECK(r.err == "error: " + (in / "*.stl").string() + ": no file matches\n");
  r = run_meshsal("batch --list " + (dir / "missing.txt").string() + " -o " + out.string(), dir);
  CHECK(r.exit_code == 1);
  CHECK(r.err == "error: " + (dir / "missing.txt").string() + ": cannot read the list file: No such file or directory\n");
  r = run_meshsal("batch " + in.string() + " -o " + out.string() + " --contact-sheet " + (dir / "sheet.jpg").string(), dir);
  CHECK(r.exit_code == 1);
  CHECK(r.err.find("--contact-sheet must be a .png file") != std::string::npos);
  CHECK_FALSE(fs::exists(out / "batch.jsonl"));
}

TEST_CASE("batch: an output that is one of the inputs fails that model and leaves the file alone", "[batch]") {
  const fs::path dir = batch_scratch("own_input");
  const fs::path in = make_batch_inputs(dir);
  // ball's output would be in/ball_saliency.ply, which is also an input mesh here.
  fs::copy_file(in / "bumpy.ply", in / "ball_saliency.ply");
  const std::string before = read_text(in / "ball_saliency.ply");
  const BatchRun r = run_meshsal("batch " + in.string() + " -o " + in.string() + " --backend cpu", dir);
  CHECK(r.exit_code == 1);
  const std::vector<std::string> lines = log_lines(in / "batch.jsonl");
  const std::string* ball = line_for(lines, "/ball.obj");
  REQUIRE(ball);
  CHECK(json_text(*ball, "status") == "failed");
  CHECK(json_text(*ball, "error") == (in / "ball_saliency.ply").string() +
                                         ": this output is one of the batch's inputs (an output never replaces an input)");
  CHECK(read_text(in / "ball_saliency.ply") == before);
  CHECK(json_text(*line_for(lines, "cube.off"), "status") == "done");
}

TEST_CASE("batch: output names stay distinct when inputs share a name", "[batch]") {
  const fs::path dir = batch_scratch("names");
  const fs::path in = make_batch_inputs(dir);
  fs::create_directories(dir / "other");
  meshsal::write_obj((dir / "other" / "ball.obj").string(), make_sphere(2.0, 1));
  meshsal::write_ply((in / "ball.ply").string(), make_sphere(1.0, 1), {});
  const BatchRun r = run_meshsal("batch " + (in / "ball.obj").string() + " " + (in / "ball.ply").string() + " " +
                                     (dir / "other" / "ball.obj").string() + " -o " + (dir / "out").string() + " --backend cpu",
                                 dir);
  INFO(r.err);
  CHECK(r.exit_code == 0);
  const std::vector<std::string> lines = log_lines(dir / "out" / "batch.jsonl");
  REQUIRE(lines.size() == 3);
  CHECK(json_text(lines[0], "name") == "ball.obj");
  CHECK(json_text(lines[1], "name") == "ball.ply");
  CHECK(json_text(lines[2], "name") == "ball.obj_2");
  CHECK(load_mesh((dir / "out" / "ball.obj_2_saliency.ply").string()).vertex_count() ==
        make_sphere(2.0, 1).vertex_count());
}

TEST_CASE("batch: on a terminal a progress line shows models done, the current one and the time left", "[batch]") {
  if (std::system("command -v script > /dev/null 2>&1") != 0) {
    meshsal_test::skip_case("script(1) (bsdutils) is missing: no terminal to test the progress line on");
    return;
  }
  const fs::path dir = batch_scratch("progress");
  const fs::path in = make_batch_inputs(dir), out = dir / "out";
  // script(1) runs the command on a pseudo-terminal and records what it drew.
  const std::string cmd = std::string(MESHSAL_CLI) + " batch " + in.string() + " -o " + out.string() +
                          " --backend cpu --view --size 64 --resolution 32 --restarts 1";
  const std::string script = "script -qec '" + cmd + "' " + (dir / "typescript").string() + " > /dev/null 2>&1 < /dev/null";
  CHECK(std::system(script.c_str()) != 0);  // -e: the batch's own status, 1 for broken.obj
  const std::string drawn = read_text(dir / "typescript");
  INFO(drawn);
  CHECK(drawn.find("[1/4] ball.obj  reading   0%") != std::string::npos);
  CHECK(drawn.find("[2/4] broken.obj") != std::string::npos);
  CHECK(drawn.find("[4/4] cube.off") != std::string::npos);
  CHECK(drawn.find(" left") != std::string::npos);  // after the first model, an estimate
  CHECK(drawn.find("batch: 4 models: 3 computed, 0 skipped, 1 failed") != std::string::npos);
  // Through a pipe (every other test here) nothing of it is drawn.
  const BatchRun piped = run_meshsal("batch " + in.string() + " -o " + out.string() + " --backend cpu --force", dir);
  CHECK(piped.err.find("[1/4]") == std::string::npos);
}
