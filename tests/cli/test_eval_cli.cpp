// meshsal eval PRED GT: one JSON object with --json holding the library's numbers, the
// table, --smooth beside the raw scores, --transfer nearest, and its errors.
#include <catch2/catch.hpp>

#include <cmath>
#include <string>
#include <vector>

#include "cli/synthetic.h"
#include "cli_run.h"
#include "json_check.h"
#include "meshsal/meshsal.h"
#include "test_io_util.h"

using meshsal_test::CliRun;
using meshsal_test::quoted;
using meshsal_test::run_cli;

namespace {

// The part of a JSON text after "KEY": (for the second object's numbers).
std::string after(const std::string& text, const std::string& key) {
  const size_t at = text.find("\"" + key + "\": ");
  return at == std::string::npos ? std::string() : text.substr(at);
}

}  // namespace

TEST_CASE("cli eval: --json holds evaluate_files' scores and the table the same with --smooth beside", "[eval][cli]") {
  meshsal_test::TempDir dir;
  const meshsal::Mesh m = meshsal::make_sphere(1.0, 2);
  const size_t n = m.vertex_count();
  std::vector<double> p(n), g(n);
  for (size_t v = 0; v < n; ++v) {
    p[v] = 1 + m.positions[3 * v];
    g[v] = std::max(0.0, double(m.positions[3 * v] + 0.3 * m.positions[3 * v + 1]));
  }
  const std::string pred = dir.file("pred.ply"), gt = dir.file("gt.ply");
  meshsal::write_ply(pred, m, {{"quality", &p}});
  meshsal::write_ply(gt, m, {{"quality", &g}});
  meshsal::EvalOptions o;
  o.smooth = 0.05;
  const meshsal::EvalReport lib = meshsal::evaluate_files(pred, gt, o);

  const CliRun r = run_cli("eval " + quoted(pred) + " " + quoted(gt) + " --smooth 0.05 --json", dir.path);
  INFO(r.err);
  REQUIRE(r.rc == 0);
  REQUIRE(meshsal_test::json_valid(r.out));
  CHECK(r.out.find("\"mesh\": \"" + pred + "\"") != std::string::npos);
  CHECK(r.out.find("\"gt_source\": \"mesh\"") != std::string::npos);
  CHECK(r.out.find("\"transfer\": \"none\"") != std::string::npos);
  CHECK(meshsal_test::json_number(r.out, "scored_vertices") == n);
  // Raw first, smoothed after: the library's numbers to the 9 digits JSON prints.
  const std::string raw = after(r.out, "raw"), smoothed = after(r.out, "smoothed");
  REQUIRE(!smoothed.empty());
  for (const auto& [key, mine, theirs] :
       {std::tuple{"cc", lib.raw.cc, lib.smoothed->cc}, std::tuple{"auc_20", lib.raw.auc_20, lib.smoothed->auc_20},
        std::tuple{"auc_5", lib.raw.auc_5, lib.smoothed->auc_5}, std::tuple{"nss", lib.raw.nss, lib.smoothed->nss},
        std::tuple{"kld", lib.raw.kld, lib.smoothed->kld}, std::tuple{"sim", lib.raw.sim, lib.smoothed->sim}}) {
    INFO(key);
    CHECK(meshsal_test::json_number(raw, key) == Approx(*mine).epsilon(1e-8));
    CHECK(meshsal_test::json_number(smoothed, key) == Approx(*theirs).epsilon(1e-8));
  }
  CHECK(meshsal_test::json_number(r.out, "smooth") == 0.05);

  // The table: a row per score, raw then smoothed; without --smooth no smoothed column and
  // "smoothed": null in JSON.
  const CliRun t = run_cli("eval " + quoted(pred) + " " + quoted(gt) + " --smooth 0.05", dir.path);
  REQUIRE(t.rc == 0);
  for (const char* row : {"\nCC ", "\nAUC-20% ", "\nAUC-5% ", "\nNSS ", "\nKLD ", "\nSIM "})
    CHECK(t.out.find(row) != std::string::npos);
  CHECK(t.out.find("smoothed (sigma 0.05 of the diagonal)") != std::string::npos);
  const CliRun plain = run_cli("eval " + quoted(pred) + " " + quoted(gt) + " --json", dir.path);
  CHECK(plain.out.find("\"smoothed\": null") != std::string::npos);
  CHECK(run_cli("eval " + quoted(pred) + " " + quoted(gt) + " -q", dir.path).out.empty());

  // A constant prediction: CC and NSS undefined, printed as such and null, with notes.
  std::vector<double> c(n, 1.0);
  const std::string flat = dir.file("flat.ply");
  meshsal::write_ply(flat, m, {{"quality", &c}});
  const CliRun u = run_cli("eval " + quoted(flat) + " " + quoted(gt), dir.path);
  REQUIRE(u.rc == 0);
  CHECK(u.out.find("undefined") != std::string::npos);
  CHECK(u.out.find("nan") == std::string::npos);
  CHECK(u.err.find("note: CC undefined: the prediction is constant") != std::string::npos);
  const CliRun uj = run_cli("eval " + quoted(flat) + " " + quoted(gt) + " --json", dir.path);
  CHECK(uj.out.find("\"cc\": null") != std::string::npos);
  CHECK(uj.out.find("\"nss\": null") != std::string::npos);
}

TEST_CASE("cli eval: text rows with unmatched rows reported and --transfer nearest and errors", "[eval][cli]") {
  meshsal_test::TempDir dir;
  const meshsal::Mesh m = meshsal::make_sphere(1.0, 1);
  const size_t n = m.vertex_count();
  std::vector<double> p(n);
  for (size_t v = 0; v < n; ++v) p[v] = m.positions[3 * v + 1];
  const std::string pred = dir.file("pred.ply");
  meshsal::write_ply(pred, m, {{"quality", &p}});
  std::string text = "x,y,z,value\n";
  for (size_t v = 0; v < n; ++v) {
    char line[160];
    std::snprintf(line, sizeof line, "%.9g,%.9g,%.9g,%d\n", m.origin[0] + m.positions[3 * v],
                  m.origin[1] + m.positions[3 * v + 1], m.origin[2] + m.positions[3 * v + 2], int(v % 3));
    text += line;
  }
  text += "3,3,3,1\n";
  const std::string rows = dir.write("gt.csv", text);
  const CliRun r = run_cli("eval " + quoted(pred) + " " + quoted(rows) + " --json", dir.path);
  INFO(r.err);
  REQUIRE(r.rc == 0);
  CHECK(r.out.find("\"gt_source\": \"text\"") != std::string::npos);
  CHECK(meshsal_test::json_number(r.out, "gt_column") == 4);
  CHECK(meshsal_test::json_number(r.out, "matched_rows") == n);
  CHECK(meshsal_test::json_number(r.out, "unmatched_rows") == 1);
  CHECK(r.out.find("\"unmatched_lines\": [" + std::to_string(n + 2) + "]") != std::string::npos);
  CHECK(r.err.find("note: 1 of " + std::to_string(n + 1) + " ground-truth rows matched no vertex") != std::string::npos);
  const CliRun t = run_cli("eval " + quoted(pred) + " " + quoted(rows) + " --transfer nearest --json", dir.path);
  REQUIRE(t.rc == 0);
  CHECK(t.out.find("\"transfer\": \"nearest\"") != std::string::npos);
  CHECK(meshsal_test::json_number(t.out, "transfer_max_distance") < 1e-6);

  // Errors: runtime errors (1) name the file and what is wrong; a bad option is a usage error (2).
  const meshsal::Mesh other = meshsal::make_sphere(1.0, 2);
  std::vector<double> q(other.vertex_count(), 1.0);
  const std::string gt_other = dir.file("other.ply");
  meshsal::write_ply(gt_other, other, {{"quality", &q}});
  const CliRun mis = run_cli("eval " + quoted(pred) + " " + quoted(gt_other), dir.path);
  CHECK(mis.rc == 1);
  CHECK(mis.err.find("--transfer nearest") != std::string::npos);
  const std::string nan_rows = dir.write("nan.txt", "0 0 1 1\n0 1 0 nan\n");
  const CliRun bad = run_cli("eval " + quoted(pred) + " " + quoted(nan_rows), dir.path);
  CHECK(bad.rc == 1);
  CHECK(bad.err.find(nan_rows + ": line 2: the value (column 4) is not finite ('nan')") != std::string::npos);
  CHECK(run_cli("eval " + quoted(pred) + " " + quoted(rows) + " --gt-column 2", dir.path).rc == 2);
  CHECK(run_cli("eval " + quoted(pred) + " " + quoted(rows) + " --transfer farthest", dir.path).rc == 2);
  CHECK(run_cli("eval " + quoted(pred) + " " + quoted(rows) + " --smooth 0.7", dir.path).rc == 2);
  const CliRun noattr = run_cli("eval " + quoted(pred) + " " + quoted(rows) + " --attribute curvature", dir.path);
  CHECK(noattr.rc == 1);
  CHECK(noattr.err.find("no per-vertex attribute 'curvature' (it has: quality;") != std::string::npos);
}
