// meshsal saliency --precision: the mixed and double GPU sweeps from the command line, and
// a bad value as a usage error.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <sys/wait.h>
#include <unistd.h>

#include "meshsal/meshsal.h"
#include "test_util.h"

using namespace meshsal;
namespace fs = std::filesystem;

namespace {

struct Run {
  int exit_code;
  std::string out, err;
};

std::string slurp(const fs::path& p) {
  std::ifstream f(p);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

Run run_cli(const std::string& args, const fs::path& dir) {
  const fs::path out = dir / "stdout.txt", err = dir / "stderr.txt";
  std::string cmd = std::string(MESHSAL_CLI) + " " + args + " > " + out.string() + " 2> " +
                    err.string() + " < /dev/null";
  int status = std::system(cmd.c_str());
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, slurp(out), slurp(err)};
}

fs::path scratch_dir() {
  fs::path d = fs::temp_directory_path() / ("meshsal_cli_precision_" + std::to_string(::getpid()));
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

std::vector<float> quality(const fs::path& ply) {
  VertexProperties props;
  load_mesh(ply.string(), &props);
  REQUIRE(props.count("quality") == 1);
  return props["quality"];
}

}  // namespace

TEST_CASE("cli: saliency --precision mixed and double agree on the gpu", "[cli][gpu][precision]") {
  MESHSAL_REQUIRE_MESH(input, "fandisk_6k.obj");
  fs::path dir = scratch_dir();
  Run mixed = run_cli("saliency " + input + " -o " + (dir / "m.ply").string() +
                          " --backend gpu --precision mixed", dir);
  INFO(mixed.err);
  REQUIRE(mixed.exit_code == 0);
  CHECK(mixed.out.find("precision  mixed (") != std::string::npos);
  Run dbl = run_cli("saliency " + input + " -o " + (dir / "d.ply").string() +
                        " --backend gpu --precision double", dir);
  REQUIRE(dbl.exit_code == 0);
  CHECK(dbl.out.find("precision  mixed") == std::string::npos);
  std::vector<float> a = quality(dir / "m.ply"), b = quality(dir / "d.ply");
  REQUIRE(a.size() == b.size());
  float mx = 0, diff = 0;
  for (size_t v = 0; v < a.size(); ++v) {
    mx = std::max(mx, std::fabs(b[v]));
    diff = std::max(diff, std::fabs(a[v] - b[v]));
  }
  CHECK(mx > 0);
  CHECK(diff <= 1e-4f * mx);
  fs::remove_all(dir);
}

TEST_CASE("cli: a bad --precision is a usage error", "[cli][precision]") {
  fs::path dir = scratch_dir();
  Run r = run_cli("saliency in.obj -o out.ply --precision single", dir);
  CHECK(r.exit_code == 2);
  CHECK(r.err.find("--precision") != std::string::npos);
  CHECK(!fs::exists(dir / "out.ply"));
  fs::remove_all(dir);
}

TEST_CASE("cli: bench has a row per sweep precision for each Vulkan device", "[cli][gpu][precision]") {
  MESHSAL_REQUIRE_MESH(input, "bunny_3k.off");
  fs::path dir = scratch_dir();
  Run r = run_cli("bench " + input + " --repeat 1 --json", dir);
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  auto count = [&](const std::string& s) {
    size_t n = 0;
    for (size_t at = r.out.find(s); at != std::string::npos; at = r.out.find(s, at + 1)) ++n;
    return n;
  };
  // The CPU row is double; each Vulkan device (lavapipe here) adds a mixed and a double row.
  CHECK(count("\"precision\": \"mixed\"") >= 1);
  CHECK(count("\"precision\": \"double\"") == count("\"precision\": \"mixed\"") + 1);
  CHECK(count("\"rechecked\": ") == count("\"mesh\": "));
  fs::remove_all(dir);
}
