// [cli][json] Every command that prints a summary prints one valid JSON object with --json
// (compare and viewpoint always do): parsed here, and its numbers checked against the files.
#include <sys/wait.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <string>

#include "core/synthetic.h"
#include "json_check.h"
#include "meshsal/meshsal.h"
#include "test_io_util.h"
#include "test_util.h"

using meshsal_test::json_number;
using meshsal_test::json_valid;

namespace {

struct Run {
  int rc = -1;
  std::string out, err;
};

Run run_cli(const std::string& args, const meshsal_test::TempDir& dir) {
  const std::string out = dir.file("stdout.txt"), err = dir.file("stderr.txt");
  const std::string cmd = std::string("'") + MESHSAL_CLI + "' " + args + " > '" + out + "' 2> '" + err + "' < /dev/null";
  const int status = std::system(cmd.c_str());
  Run r;
  r.rc = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.out = meshsal_test::read_file(out);
  r.err = meshsal_test::read_file(err);
  return r;
}

std::string q(const std::string& s) { return "'" + s + "'"; }

// One line holding one JSON object.
void check_one_object(const std::string& out) {
  INFO(out);
  CHECK(json_valid(out));
  CHECK(out.front() == '{');
  CHECK(std::count(out.begin(), out.end(), '\n') == 1);
}

}  // namespace

TEST_CASE("json checker: accepts JSON, refuses near misses", "[cli][json]") {
  CHECK(json_valid("{\"a\": [1, -2.5e3, true, null, \"x\\n\\u00e9\"], \"b\": {}}\n"));
  CHECK(json_valid("[]"));
  CHECK_FALSE(json_valid("{\"a\": 1,}"));
  CHECK_FALSE(json_valid("{\"a\": nan}"));
  CHECK_FALSE(json_valid("{\"a\": 01}"));
  CHECK_FALSE(json_valid("{\"a\": 1} {}"));
  CHECK_FALSE(json_valid("{a: 1}"));
  CHECK_FALSE(json_valid("{\"a\": \"tab\there\"}"));
  CHECK(json_number("{\"x\": 1, \"y\": 2.5}", "y") == 2.5);
}

TEST_CASE("cli --json: saliency, simplify, compare and viewpoint print one JSON object", "[cli][json]") {
  meshsal_test::TempDir dir;
  const meshsal::Mesh bumpy = meshsal::make_bumpy_sphere(3);
  const std::string mesh = dir.file("bumpy \"quoted\".ply");
  meshsal::write_ply(mesh, bumpy, {});
  const std::string sal = dir.file("sal.ply");

  Run r = run_cli("saliency " + q(mesh) + " -o " + q(sal) + " --backend cpu --json", dir);
  REQUIRE(r.rc == 0);
  check_one_object(r.out);
  CHECK(r.out.find("\"mesh\": \"" + dir.file("bumpy \\\"quoted\\\".ply") + "\"") != std::string::npos);
  CHECK(r.out.find("\"device\": \"cpu (") != std::string::npos);
  CHECK(r.out.find("\"gaussian_sweep\": ") != std::string::npos);
  CHECK(json_number(r.out, "vertices") == double(bumpy.vertex_count()));
  CHECK(json_number(r.out, "faces") == double(bumpy.triangle_count()));
  CHECK(json_number(r.out, "seconds") > 0);
  // The statistics of S match the quality the PLY holds (floats there).
  meshsal::VertexProperties props;
  meshsal::load_mesh(sal, &props);
  std::vector<float> s = props.at("quality");
  std::sort(s.begin(), s.end());
  double mean = 0;
  for (float x : s) mean += x;
  mean /= double(s.size());
  CHECK(json_number(r.out, "min") == Approx(s.front()).margin(1e-6));
  CHECK(json_number(r.out, "max") == Approx(s.back()).epsilon(1e-6));
  CHECK(json_number(r.out, "mean") == Approx(mean).epsilon(1e-5));
  CHECK(json_number(r.out, "p50") == Approx(s[(s.size() + 1) / 2 - 1]).epsilon(1e-6));
  CHECK(json_number(r.out, "p99") == Approx(s[size_t(std::ceil(0.99 * double(s.size()))) - 1]).epsilon(1e-6));
  CHECK(json_number(r.out, "min") <= json_number(r.out, "p10"));
  CHECK(json_number(r.out, "p90") <= json_number(r.out, "max"));
  // The text summary holds the same statistics.
  r = run_cli("saliency " + q(mesh) + " -o " + q(sal) + " --backend cpu", dir);
  CHECK(r.out.find("S          min ") != std::string::npos);

  const std::string small = dir.file("small.obj");
  r = run_cli("simplify " + q(mesh) + " -o " + q(small) + " --ratio 0.25 --saliency-from " + q(sal) + " --json", dir);
  REQUIRE(r.rc == 0);
  check_one_object(r.out);
  const meshsal::Mesh simplified = meshsal::load_mesh(small);
  CHECK(json_number(r.out, "output_faces") == double(simplified.triangle_count()));
  CHECK(json_number(r.out, "input_faces") == double(bumpy.triangle_count()));
  CHECK(r.out.find("\"weights\": \"saliency\"") != std::string::npos);

  r = run_cli("simplify " + q(mesh) + " -o " + q(dir.file("same.obj")) + " --target-faces 100000000 --json", dir);
  REQUIRE(r.rc == 0);
  check_one_object(r.out);
  CHECK(r.out.find("\"unchanged\": true") != std::string::npos);

  r = run_cli("compare " + q(mesh) + " " + q(small) + " --saliency-from " + q(sal) + " --samples 2000", dir);
  REQUIRE(r.rc == 0);
  check_one_object(r.out);
  const double diag = json_number(r.out, "diagonal");
  REQUIRE(diag > 0);
  for (const char* d : {"hausdorff", "rms", "forward_max", "backward_max", "salient_error"})
    CHECK(json_number(r.out, std::string(d) + "_percent") == Approx(100 * json_number(r.out, d) / diag));
  CHECK(json_number(r.out, "hausdorff") > 0);

  r = run_cli("viewpoint " + q(mesh) + " --saliency-from " + q(sal) + " --backend cpu --restarts 1 --resolution 64", dir);
  REQUIRE(r.rc == 0);
  check_one_object(r.out);
  CHECK(json_number(r.out, "vertices") == double(bumpy.vertex_count()));
}
