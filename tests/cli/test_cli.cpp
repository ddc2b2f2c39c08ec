// The meshsal executable end to end: outputs, exit codes and one-line errors.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>
#include <sys/wait.h>

#include "meshsal/meshsal.h"
#include "saliency/saliency.h"
#include "cli/synthetic.h"
#include "cli_run.h"
#include "test_util.h"

using namespace meshsal;
namespace fs = std::filesystem;

using namespace meshsal_test;  // cli_run.h: run_cli, scratch_dir, read_file

namespace {

void write_text(const fs::path& p, const std::string& text) {
  std::ofstream f(p, std::ios::binary);
  f << text;
}

// A failed run: exit code 1 (not a signal), exactly one line on stderr starting "error: ".
void check_clean_failure(const CliRun& r) {
  INFO("stderr: " << r.err);
  CHECK(r.rc == 1);
  CHECK(r.err.rfind("error: ", 0) == 0);
  CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
}

}  // namespace

TEST_CASE("cli: saliency writes the SPEC PLY with the CPU path's numbers", "[cli]") {
  MESHSAL_REQUIRE_MESH(input, "bunny_3k.off");
  fs::path dir = scratch_dir("cli_saliency");
  fs::path out = dir / "bunny.ply";
  CliRun r = run_cli("saliency " + input + " -o " + out.string() + " --backend cpu --dump-scales", dir);
  INFO(r.err);
  REQUIRE(r.rc == 0);
  CHECK(r.out.find("vertices   3485") != std::string::npos);
  CHECK(r.out.find("pairs/s") != std::string::npos);

  LoadedMesh read = read_mesh(out.string());
  const Mesh& written = read.mesh;
  VertexProperties& props = read.properties;
  Mesh original = load_mesh(input);
  CHECK(meshsal_test::world_floats(written) == meshsal_test::world_floats(original));
  CHECK(written.triangles == original.triangles);
  SaliencyResult expected = compute_saliency_cpu(original, {});
  for (const char* name : {"quality", "curvature", "saliency_raw_0", "saliency_raw_4", "red", "green", "blue"})
    REQUIRE(props.count(name) == 1);
  for (size_t v = 0; v < original.vertex_count(); ++v) {
    REQUIRE(props["quality"][v] == Approx(float(expected.saliency[v])).margin(1e-6));
    REQUIRE(props["curvature"][v] == Approx(float(expected.curvature[v])).margin(1e-4));
  }
  fs::remove_all(dir);
}

TEST_CASE("cli: bad input gets one error line and exit code 1", "[cli]") {
  fs::path dir = scratch_dir("cli_bad");
  const std::string out = (dir / "out.ply").string();
  SECTION("missing file") { check_clean_failure(run_cli("saliency " + (dir / "nope.obj").string() + " -o " + out, dir)); }
  SECTION("unknown extension") {
    write_text(dir / "mesh.stl", "solid x\n");
    check_clean_failure(run_cli("saliency " + (dir / "mesh.stl").string() + " -o " + out, dir));
  }
  SECTION("garbled PLY") {
    write_text(dir / "g.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nend_header\n1 2\nxyz\n");
    check_clean_failure(run_cli("saliency " + (dir / "g.ply").string() + " -o " + out, dir));
  }
  SECTION("only degenerate triangles") {
    write_text(dir / "d.obj", "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n");
    check_clean_failure(run_cli("saliency " + (dir / "d.obj").string() + " -o " + out, dir));
  }
  SECTION("NaN coordinate") {
    write_text(dir / "n.obj", "v 0 0 0\nv 1 0 nan\nv 0 1 0\nf 1 2 3\n");
    check_clean_failure(run_cli("saliency " + (dir / "n.obj").string() + " -o " + out, dir));
  }
  SECTION("index out of range") {
    write_text(dir / "i.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n");
    check_clean_failure(run_cli("saliency " + (dir / "i.off").string() + " -o " + out, dir));
  }
  SECTION("bad scales") {
    write_text(dir / "t.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    // A usage error: exit 2, the option and its range named.
    CliRun r = run_cli("saliency " + (dir / "t.obj").string() + " -o " + out + " --scales 2,x", dir);
    CHECK(r.rc == 2);
    CHECK(r.err.rfind("error: --scales: must be a comma-separated list of numbers in (0, 100], got '2,x'", 0) == 0);
  }
  SECTION("output not .ply") {
    write_text(dir / "t.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    check_clean_failure(run_cli("saliency " + (dir / "t.obj").string() + " -o " + (dir / "o.txt").string(), dir));
  }
  SECTION("output folder missing") {
    write_text(dir / "t.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    check_clean_failure(run_cli("saliency " + (dir / "t.obj").string() + " -o " + (dir / "no/such/o.ply").string(), dir));
  }
  CHECK_FALSE(fs::exists(out));
  fs::remove_all(dir);
}

TEST_CASE("cli: a failed run leaves an earlier output untouched", "[cli]") {
  fs::path dir = scratch_dir("cli_keep");
  const fs::path out = dir / "out.ply";
  write_text(out, "previous result");
  write_text(dir / "bad.obj", "v 0 0 0\nf 1 2 3\n");
  check_clean_failure(run_cli("saliency " + (dir / "bad.obj").string() + " -o " + out.string(), dir));
  CHECK(read_file(out) == "previous result");
  fs::remove_all(dir);
}

namespace {

// The entries of a CLI11 help section (the lines after the line that starts with `title`, up
// to a blank line): the first word of each entry -> the rest of its text (its continuation
// lines, indented further, joined with single spaces).
std::map<std::string, std::string> help_entries(const std::string& help, const std::string& title) {
  std::map<std::string, std::string> entries;
  std::istringstream lines(help);
  std::string line, current;
  bool in = false;
  while (std::getline(lines, line)) {
    if (!in) {
      in = line.rfind(title, 0) == 0;
      continue;
    }
    if (line.empty()) break;
    const size_t text = line.find_first_not_of(' ');
    if (text == 2) {  // a new entry: "  NAME  description"
      const size_t end = line.find(' ', text);
      current = line.substr(text, end - text);
      const size_t desc = end == std::string::npos ? std::string::npos : line.find_first_not_of(' ', end);
      entries[current] = desc == std::string::npos ? "" : line.substr(desc);
    } else if (!current.empty() && text != std::string::npos) {
      std::string& e = entries[current];
      e += (e.empty() ? "" : " ") + line.substr(text);
    }
  }
  return entries;
}

std::string first_line(const std::string& text) { return text.substr(0, text.find('\n')); }

template <class T>
std::string text_of(const T& value) {
  std::ostringstream s;
  s << value;
  return s.str();
}

}  // namespace

TEST_CASE("cli: help explains every command and option", "[cli]") {
  fs::path dir = scratch_dir("cli_help");
  // The top level lists every command with the one-line summary its own --help opens with.
  CliRun top = run_cli("--help", dir);
  CHECK(top.rc == 0);
  const auto commands = help_entries(top.out, "Subcommands:");
  std::vector<std::string> names;
  for (const auto& [name, summary] : commands) names.push_back(name);
  CHECK(names == std::vector<std::string>{"batch", "bench", "compare", "demo", "devices", "eval", "render", "saliency",
                                          "simplify", "view", "viewpoint"});
  for (const auto& [name, summary] : commands) {
    const CliRun own = run_cli(name + " --help", dir);
    INFO("meshsal " << name << " --help:\n" << own.out);
    CHECK(own.rc == 0);
    CHECK(summary.size() > 20);
    CHECK(first_line(own.out) == summary);
  }
  // saliency --help: every option, with its type, range and default where it has one; the
  // library's defaults where the CLI takes them (only --backend and --precision have their own).
  CliRun sal = run_cli("saliency --help", dir);
  CHECK(sal.rc == 0);
  const SaliencyOptions lib;
  std::string scales;
  for (double k : lib.scales) scales += (scales.empty() ? "" : ",") + text_of(k);
  const std::map<std::string, std::string> expected{
      {"-h,--help", "Print this"},
      {"-o,--output", "TEXT REQUIRED"},
      {"--backend", "TEXT=auto"},
      {"--model", "TEXT:{lee2005,perceptual,exposure,centre,center,height,rarity,coarse}=" +
                      std::string(model_name(lib.model))},
      {"--up", "TEXT:{x,y,z,-x,-y,-z}=y"},
      {"--precision", "TEXT:{auto,mixed,double}=auto"},
      {"--method", "TEXT:{exact,fast,auto}=" + std::string(lib.method == Method::Exact ? "exact" : "?")},
      {"--device", "INT:in [-1, 255]"},
      {"--scales", "TEXT:list=" + scales},
      {"--eps-frac", "FLOAT:in (0, 0.1]=" + text_of(lib.eps_frac)},
      {"--dump-scales", "Also write `curvature`"},
      {"--threads", "UINT:in [0, 1024]=" + text_of(lib.threads)},
      {"-q,--quiet", "Print nothing on success"},
      {"--tiles", "UINT:in [0, " + std::to_string(kMaxTiles) + "]"},
      {"--memory-limit", "TEXT"},
      {"--temp-dir", "TEXT"},
      {"--json", "Print the summary as one JSON object"}};
  const auto options = help_entries(sal.out, "Options:");
  INFO("meshsal saliency --help:\n" << sal.out);
  std::vector<std::string> listed, known;
  for (const auto& entry : options) listed.push_back(entry.first);
  for (const auto& entry : expected) known.push_back(entry.first);
  CHECK(listed == known);  // no option missing, none undocumented here
  for (const auto& [name, start] : expected) {
    INFO(name);
    const auto it = options.find(name);
    if (it == options.end()) continue;  // reported above
    CHECK(it->second.rfind(start, 0) == 0);
    CHECK(it->second.size() > start.size() + 10);  // and a description
  }
  CliRun none = run_cli("", dir);
  CHECK(none.rc != 0);
  CHECK(none.rc != -1);
  fs::remove_all(dir);
}

TEST_CASE("cli: demo writes a saliency PLY where the feature wins", "[cli]") {
  fs::path dir = scratch_dir("cli_demo");
  CliRun r = run_cli("demo -o " + (dir / "out").string() + " --subdivisions 5 --backend cpu", dir);
  INFO(r.err);
  REQUIRE(r.rc == 0);
  LoadedMesh read = read_mesh((dir / "out" / "bumpy_sphere_saliency.ply").string());
  const Mesh& m = read.mesh;
  const VertexProperties& props = read.properties;
  CHECK(m.vertex_count() == 10242);
  REQUIRE(props.count("quality") == 1);
  CHECK(r.out.find("unique feature") != std::string::npos);
  Mesh plain = load_mesh((dir / "out" / "simplified_plain.obj").string());
  Mesh salient = load_mesh((dir / "out" / "simplified_saliency.obj").string());
  CHECK(plain.triangle_count() == salient.triangle_count());
  CHECK(salient.triangle_count() < m.triangle_count() / 20);
  fs::remove_all(dir);
}

TEST_CASE("cli: bench --json escapes model names", "[cli]") {
  // A file name with a quote and a backslash: the JSON must still parse to the same name.
  fs::path dir = scratch_dir("cli_bench_json");
  const std::string name = "odd \"name\" \\ 1.obj";
  write_obj((dir / name).string(), make_sphere(1.0, 2));
  CliRun r = run_cli("bench --json --repeat 1 --threads 1 '" + (dir / name).string() + "'", dir);
  INFO(r.err);
  REQUIRE(r.rc == 0);
  CHECK(r.out.find("\"name\": \"odd \\\"name\\\" \\\\ 1.obj\"") != std::string::npos);
  CHECK(r.out.find("\"device\": \"cpu") != std::string::npos);
  fs::remove_all(dir);
}
