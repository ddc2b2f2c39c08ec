// [cli][json] Every command that prints a summary prints one valid JSON object with --json
// (compare and viewpoint always do): parsed here, and its numbers checked against the files.
#include <sys/wait.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <string>
#include <vector>

#include "cli/synthetic.h"
#include "json_check.h"
#include "meshsal/meshsal.h"
#include "test_io_util.h"
#include "cli_run.h"
#include "test_util.h"

using meshsal_test::json_number;
using meshsal_test::json_valid;

using meshsal_test::CliRun;
using meshsal_test::read_file;
using meshsal_test::run_cli;

namespace {

std::string q(const std::string& s) { return "'" + s + "'"; }

// One line holding one JSON object.
void check_one_object(const std::string& out) {
  INFO(out);
  CHECK(json_valid(out));
  CHECK(out.front() == '{');
  CHECK(std::count(out.begin(), out.end(), '\n') == 1);
}

// Every key of a JSON text (object keys at any depth), in order.
std::vector<std::string> json_keys(const std::string& text) {
  std::vector<std::string> keys;
  for (size_t i = 0; i < text.size(); ++i) {
    if (text[i] != '"') continue;
    size_t j = i + 1;
    while (j < text.size() && text[j] != '"') j += text[j] == '\\' ? 2 : 1;
    size_t k = j + 1;
    while (k < text.size() && text[k] == ' ') ++k;
    if (k < text.size() && text[k] == ':') keys.push_back(text.substr(i + 1, j - i - 1));
    i = j;
  }
  return keys;
}

bool snake_case(const std::string& key) {
  if (key.empty() || !std::islower(static_cast<unsigned char>(key[0]))) return false;
  for (char c : key)
    if (!(std::islower(static_cast<unsigned char>(c)) || std::isdigit(static_cast<unsigned char>(c)) || c == '_'))
      return false;
  return true;
}

bool has_key(const std::vector<std::string>& keys, const std::string& key) {
  return std::find(keys.begin(), keys.end(), key) != keys.end();
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

  CliRun r = run_cli("saliency " + q(mesh) + " -o " + q(sal) + " --backend cpu --json", dir);
  REQUIRE(r.rc == 0);
  check_one_object(r.out);
  CHECK(r.out.find("\"mesh\": \"" + dir.file("bumpy \\\"quoted\\\".ply") + "\"") != std::string::npos);
  CHECK(r.out.find("\"device\": \"cpu (") != std::string::npos);
  CHECK(r.out.find("\"gaussian_sweep\": ") != std::string::npos);
  CHECK(json_number(r.out, "vertices") == double(bumpy.vertex_count()));
  CHECK(json_number(r.out, "faces") == double(bumpy.triangle_count()));
  CHECK(json_number(r.out, "seconds") > 0);
  // The statistics of S match the quality the PLY holds (floats there).
  const meshsal::VertexProperties props = meshsal::read_mesh(sal).properties;
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
  CHECK(r.out.find("\"weights\": \"balanced\"") != std::string::npos);  // the default

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

TEST_CASE("cli --json: every command that prints a summary follows one convention", "[cli][json]") {
  meshsal_test::TempDir dir;
  const meshsal::Mesh bumpy = meshsal::make_bumpy_sphere(2);
  const std::string mesh = dir.file("bumpy.ply"), sal = dir.file("sal.ply"), small = dir.file("small.obj");
  meshsal::write_ply(mesh, bumpy, {});
  const std::string m = q(mesh);
  // CliRun in this order: simplify needs saliency's file, compare simplify's.
  const std::pair<const char*, std::string> commands[] = {
      {"saliency", "saliency " + m + " -o " + q(sal) + " --backend cpu --json"},
      {"simplify", "simplify " + m + " -o " + q(small) + " --ratio 0.25 --backend cpu --json"},
      {"compare", "compare " + m + " " + q(small) + " --saliency-from " + q(sal) + " --samples 2000 --json"},
      {"viewpoint", "viewpoint " + m + " --saliency-from " + q(sal) + " --backend cpu --restarts 1 --resolution 64 --json"},
      {"render", "render " + m + " --saliency-from " + q(sal) + " --theta 30 --phi 10 --size 64 -o " +
                     q(dir.file("r.png")) + " --json"},
      {"bench", "bench " + m + " --repeat 1 --threads 1 --json"},
  };
  for (const auto& [name, args] : commands) {
    INFO(name);
    const CliRun r = run_cli(args, dir);
    INFO(r.err);
    REQUIRE(r.rc == 0);
    check_one_object(r.out);
    const std::vector<std::string> keys = json_keys(r.out);
    INFO(r.out);
    for (const std::string& k : keys) {
      INFO("key " << k);
      CHECK(snake_case(k));
    }
    // mesh (the input as given), seconds and device; bench has them in each of its rows.
    CHECK(r.out.find("\"mesh\": \"" + mesh + "\"") != std::string::npos);
    CHECK(json_number(r.out, "seconds") >= 0);
    CHECK(r.out.find("\"device\": \"cpu") != std::string::npos);
    // Every distance also in % of the bounding-box diagonal, and the other way round.
    for (const std::string& k : keys) {
      const size_t p = k.rfind("_percent");
      if (p == std::string::npos || p + 8 != k.size()) continue;
      const std::string base = k.substr(0, p);
      INFO("distance " << base);
      REQUIRE(has_key(keys, base));
      CHECK(json_number(r.out, k) == Approx(100 * json_number(r.out, base) / json_number(r.out, "diagonal")));
    }
  }
  // compare: each distance both ways; its device is the CPU (saliency read from the file).
  const CliRun c = run_cli("compare " + m + " " + q(small) + " --saliency-from " + q(sal) + " --samples 2000", dir);
  REQUIRE(c.rc == 0);
  for (const char* d : {"hausdorff", "rms", "forward_max", "forward_rms", "backward_max", "backward_rms", "salient_error"})
    CHECK(has_key(json_keys(c.out), std::string(d) + "_percent"));
  CHECK(c.out.find("\"saliency_source\": \"" + sal + "\"") != std::string::npos);
}

TEST_CASE("cli --json: render --json gives the view, U and the picture, bench one object with rows", "[cli][json]") {
  meshsal_test::TempDir dir;
  // A sphere whose saliency is max(0, x): seen from +x (theta 90, y up) U is most of the total.
  const meshsal::Mesh s = meshsal::make_sphere(1.0, 3);
  std::vector<double> qv(s.vertex_count());
  for (size_t i = 0; i < qv.size(); ++i) qv[i] = std::max(0.0, double(s.positions[3 * i]));
  const std::string mesh = dir.file("s.ply"), png = dir.file("r.png");
  meshsal::write_ply(mesh, s, {{"quality", &qv}});
  CliRun r = run_cli("render " + q(mesh) + " --theta 90 --phi 0 --size 64 -o " + q(png) + " --json", dir);
  REQUIRE(r.rc == 0);
  check_one_object(r.out);
  INFO(r.out);
  CHECK(r.out.find("\"output\": \"" + png + "\"") != std::string::npos);
  CHECK(json_number(r.out, "theta_deg") == Approx(90));
  CHECK(json_number(r.out, "phi_deg") == Approx(0).margin(1e-9));
  CHECK(json_number(r.out, "theta") == Approx(3.14159265358979 / 2));
  CHECK(r.out.find("\"direction\": [1, ") != std::string::npos);
  CHECK(r.out.find("\"best\": false") != std::string::npos);
  double total = 0;
  for (double x : qv) total += x;
  CHECK(json_number(r.out, "visible_score") > 0.9 * total);  // the whole +x half is in view
  CHECK(json_number(r.out, "visible_fraction") == Approx(json_number(r.out, "visible_score") / total).epsilon(1e-3));
  CHECK(meshsal_test::read_file(png).size() > 100);
  CHECK(r.err.empty() == false);  // the note that the PLY brings its own saliency, on stderr

  // --best: the view found, in the JSON too (looking from +x).
  r = run_cli("render " + q(mesh) + " --best --backend cpu --size 64 -o " + q(png) + " --json", dir);
  REQUIRE(r.rc == 0);
  check_one_object(r.out);
  CHECK(r.out.find("\"best\": true") != std::string::npos);
  CHECK(std::fabs(json_number(r.out, "theta_deg") - 90) < 15);
  CHECK(std::fabs(json_number(r.out, "phi_deg")) < 15);
  // --grey: no score, so no U.
  r = run_cli("render " + q(mesh) + " --grey --size 64 -o " + q(png) + " --json", dir);
  REQUIRE(r.rc == 0);
  check_one_object(r.out);
  CHECK(r.out.find("\"visible_score\": null") != std::string::npos);

  // bench: one object; a row per device, the stages' keys snake_case.
  r = run_cli("bench " + q(mesh) + " --repeat 1 --threads 1 --json", dir);
  REQUIRE(r.rc == 0);
  check_one_object(r.out);
  CHECK(r.out.find("\"rows\": [{\"mesh\": \"" + mesh + "\", \"name\": \"s.ply\"") != std::string::npos);
  CHECK(r.out.find("\"gaussian_sweep\": ") != std::string::npos);
  CHECK(json_number(r.out, "vertices") == double(s.vertex_count()));
}
