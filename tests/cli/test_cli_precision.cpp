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
#include "cli_run.h"
#include "test_util.h"

using namespace meshsal;
namespace fs = std::filesystem;

using namespace meshsal_test;  // cli_run.h: run_cli, scratch_dir, check_usage_error

namespace {

std::vector<float> quality(const fs::path& ply) {
  VertexProperties props = read_mesh(ply.string()).properties;
  REQUIRE(props.count("quality") == 1);
  return props["quality"];
}

}  // namespace

TEST_CASE("cli: saliency --precision mixed and double agree on the gpu", "[cli][gpu][precision]") {
  MESHSAL_REQUIRE_MESH(input, "fandisk_6k.obj");
  fs::path dir = scratch_dir("cli_precision");
  CliRun mixed = run_cli("saliency " + input + " -o " + (dir / "m.ply").string() +
                          " --backend gpu --precision mixed", dir);
  INFO(mixed.err);
  REQUIRE(mixed.rc == 0);
  CHECK(mixed.out.find("precision  mixed (") != std::string::npos);
  CliRun dbl = run_cli("saliency " + input + " -o " + (dir / "d.ply").string() +
                        " --backend gpu --precision double", dir);
  REQUIRE(dbl.rc == 0);
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
  const fs::path dir = scratch_dir("cli_precision");
  check_usage_error("saliency in.obj -o out.ply --precision single", "--precision", dir);
  fs::remove_all(dir);
}

TEST_CASE("cli: bench has a row per sweep precision for each Vulkan device", "[cli][gpu][precision]") {
  MESHSAL_REQUIRE_MESH(input, "bunny_3k.off");
  fs::path dir = scratch_dir("cli_precision");
  CliRun r = run_cli("bench " + input + " --repeat 1 --json", dir);
  INFO(r.err);
  REQUIRE(r.rc == 0);
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
