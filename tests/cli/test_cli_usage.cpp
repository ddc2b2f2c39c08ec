// [cli] Usage errors exit 2 in every command, runtime errors 1 (issue 22): an unknown
// option, a missing value, a bad number, a missing input and an unknown command; an option
// name said once in its message; render -q and its "wrote" line; devices --json.
#include <sstream>
#include <string>
#include <vector>

#include "cli_run.h"
#include "json_check.h"
#include "test_io_util.h"
#include "test_util.h"

using meshsal_test::CliRun;
using meshsal_test::run_cli;
using meshsal_test::TempDir;

namespace {

std::string q(const std::string& s) { return "'" + s + "'"; }

// The commands `meshsal --help` lists (CLI11: "SUBCOMMANDS:" then one indented line each).
std::vector<std::string> listed_commands() {
  const CliRun r = run_cli("--help");
  std::vector<std::string> names;
  std::istringstream lines(r.out);
  std::string line;
  bool in_list = false;
  while (std::getline(lines, line)) {
    if (line.find("ubcommands") != std::string::npos || line.find("UBCOMMANDS") != std::string::npos) {
      in_list = true;
      continue;
    }
    if (!in_list) continue;
    if (line.size() < 3 || line[0] != ' ' || line[2] == ' ') continue;  // a help text's second line
    std::istringstream words(line);
    std::string name;
    words >> name;
    if (!name.empty()) names.push_back(name);
  }
  return names;
}

}  // namespace

TEST_CASE("cli: every command exits 2 on an unknown option, a missing value, a missing input", "[cli]") {
  const std::vector<std::string> commands = listed_commands();
  INFO("meshsal --help lists: " << commands.size() << " commands");
  REQUIRE(commands.size() >= 9);
  TempDir dir;
  for (const std::string& c : commands) {
    INFO("command: " << c);
    CliRun r = run_cli(c + " --no-such-option", dir);
    INFO(r.err);
    CHECK(r.rc == 2);
    CHECK(r.err.rfind("error: ", 0) == 0);
    CHECK(r.err.find('\n') == r.err.size() - 1);  // one line
    r = run_cli(c + " --threads", dir);  // a missing value (or an unknown option)
    INFO(r.err);
    CHECK(r.rc == 2);
    r = run_cli(c + " --threads lots", dir);  // a bad number (or an unknown option)
    INFO(r.err);
    CHECK(r.rc == 2);
    if (c != "devices" && c != "demo" && c != "bench") {  // these need no input
      r = run_cli(c, dir);
      INFO(r.err);
      CHECK(r.rc == 2);
    }
  }
  for (const char* args : {"salincy x.obj", "", "--bogus", "saliency a.obj -o b.ply extra"}) {
    const CliRun r = run_cli(args, dir);
    INFO(args << "\n" << r.err);
    CHECK(r.rc == 2);
    CHECK(r.err.rfind("error: ", 0) == 0);
  }
}

TEST_CASE("cli: bad numbers and choices are usage errors (2), bad files runtime errors (1)", "[cli]") {
  TempDir dir;
  const std::string obj = dir.write("t.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  const std::string out = dir.file("o.ply"), png = dir.file("o.png");
  for (const std::string& args : std::vector<std::string>{
           "saliency " + q(obj) + " -o " + q(out) + " --eps-frac nan",
           "saliency " + q(obj) + " -o " + q(out) + " --scales 1,x",
           "saliency " + q(obj) + " -o " + q(out) + " --method quick",
           "saliency " + q(obj) + " -o " + q(out) + " --backend tpu",
           "saliency " + q(obj) + " -o " + q(out) + " --device 9999",
           "saliency " + q(obj),
           "simplify " + q(obj) + " -o " + q(out) + " --ratio 2",
           "simplify " + q(obj) + " -o " + q(out) + " --ratio 0.5 --weights paper",
           "simplify " + q(obj) + " -o " + q(out),
           "simplify " + q(obj) + " -o " + q(out) + " --target-faces",
           "render " + q(obj) + " -o " + q(png) + " --size 3",
           "render " + q(obj) + " -o " + q(png) + " --up w",
           "render " + q(obj) + " -o " + q(png) + " --color-range 5",
           "render " + q(obj) + " -o " + q(png) + " --score beauty",
           "render " + q(obj) + " -o " + q(png) + " --backend tpu --grey",
           "render " + q(obj) + " -o " + q(png) + " --compare " + q(obj),
           "viewpoint " + q(obj) + " --backend tpu",
           "viewpoint " + q(obj) + " --up w",
           "viewpoint " + q(obj) + " --views -3",
           "viewpoint " + q(obj) + " --score beauty",
           "compare " + q(obj),
           "compare " + q(obj) + " " + q(obj) + " --samples x",
           "bench --repeat 0",
           "demo --subdivisions x",
       }) {
    const CliRun r = run_cli(args, dir);
    INFO(args << "\n" << r.err);
    CHECK(r.rc == 2);
    CHECK(r.err.rfind("error: ", 0) == 0);
  }
  for (const std::string& args : std::vector<std::string>{
           "saliency " + q(dir.file("missing.obj")) + " -o " + q(out),
           "simplify " + q(dir.file("missing.obj")) + " -o " + q(out) + " --ratio 0.5",
           "render " + q(dir.file("missing.obj")) + " -o " + q(png),
           "viewpoint " + q(dir.file("missing.obj")),
       }) {
    const CliRun r = run_cli(args, dir);
    INFO(args << "\n" << r.err);
    CHECK(r.rc == 1);
    CHECK(r.err.find("No such file") != std::string::npos);
  }
}

TEST_CASE("cli: an option's name is said once in its error", "[cli]") {
  TempDir dir;
  const std::string obj = dir.write("t.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  for (const std::string& cmd : std::vector<std::string>{"render " + q(obj) + " -o " + q(dir.file("o.png")),
                                 "viewpoint " + q(obj)}) {
    for (const char* range : {"2,1", "5", "0,200%"}) {
      const CliRun r = run_cli(cmd + " --color-range " + range, dir);
      INFO(r.err);
      CHECK(r.rc == 2);
      const size_t first = r.err.find("--color-range");
      REQUIRE(first != std::string::npos);
      CHECK(r.err.find("--color-range", first + 1) == std::string::npos);
    }
  }
  const CliRun r = run_cli("render " + q(obj) + " -o " + q(dir.file("o.png")) + " --color-range 2,1", dir);
  CHECK(r.err == "error: --color-range: LO must be below HI, got '2,1' (see --help)\n");
  for (const char* scales : {"1,x", "", "0"}) {
    const CliRun s = run_cli("saliency " + q(obj) + " -o " + q(dir.file("o.ply")) + " --scales '" + scales + "'", dir);
    INFO(s.err);
    CHECK(s.rc == 2);
    const size_t first = s.err.find("--scales");
    REQUIRE(first != std::string::npos);
    CHECK(s.err.find("--scales", first + 1) == std::string::npos);
  }
}

TEST_CASE("cli render: says what it wrote, -q prints nothing", "[cli][view]") {
  TempDir dir;
  const std::string obj = dir.write("t.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 2 3\nf 1 3 4\nf 1 4 2\nf 2 4 3\n");
  const std::string png = dir.file("o.png");
  CliRun r = run_cli("render " + q(obj) + " -o " + q(png) + " --grey --size 64", dir);
  INFO(r.err);
  REQUIRE(r.rc == 0);
  // One line: the file and the picture's size (the title and colour bar around the view).
  CHECK(r.out.rfind("wrote " + png + " (", 0) == 0);
  CHECK(r.out.find('x', png.size()) != std::string::npos);
  CHECK(r.out.size() > 3);
  CHECK(r.out.substr(r.out.size() - 2) == ")\n");
  CHECK(r.out.find('\n') == r.out.size() - 1);
  r = run_cli("render " + q(obj) + " -o " + q(png) + " --grey --size 64 -q", dir);
  CHECK(r.rc == 0);
  CHECK(r.out.empty());
  CHECK(r.err.empty());
  r = run_cli("render " + q(obj) + " -o " + q(png) + " --best --backend cpu --size 64 --quiet", dir);
  INFO(r.err);
  CHECK(r.rc == 0);
  CHECK(r.out.empty());
  CHECK(r.err.empty());  // no "best view:" line either
  r = run_cli("render " + q(obj) + " -o " + q(png) + " --grey --size 64 --json", dir);
  CHECK(r.rc == 0);
  CHECK(r.out.find("wrote") == std::string::npos);  // the JSON replaces the line
}

TEST_CASE("cli devices --json: one JSON array of the library's devices", "[cli]") {
  TempDir dir;
  const CliRun r = run_cli("devices --json", dir);
  INFO(r.err);
  REQUIRE(r.rc == 0);
  REQUIRE(!r.out.empty());
  CHECK(r.out.front() == '[');
  CHECK(r.out.substr(r.out.size() - 2) == "]\n");
  CHECK(r.out.find('\n') == r.out.size() - 1);
  if (r.out != "[]\n") {
    for (const char* key : {"\"index\":", "\"name\":", "\"type\":", "\"device_local_bytes\":", "\"api_version\":",
                            "\"has_compute\":"})
      CHECK(r.out.find(key) != std::string::npos);
    CHECK(meshsal_test::json_valid(r.out.substr(1, r.out.find('}') )));
  }
}
