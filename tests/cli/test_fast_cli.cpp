// --method on the command line: every saliency-computing command takes it, a bad value is a
// usage error, and bench --method fast reports the error against exact.
#include <catch2/catch.hpp>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <sys/wait.h>
#include <unistd.h>

#include "meshsal/meshsal.h"
#include "cli_run.h"
#include "test_util.h"

namespace fs = std::filesystem;

using namespace meshsal_test;  // cli_run.h: run_cli, scratch_dir, check_usage_error

TEST_CASE("cli: every command that computes saliency takes --method", "[cli][fast]") {
  fs::path dir = scratch_dir("fast_cli");
  for (const char* cmd : {"saliency", "simplify", "viewpoint", "render", "demo", "compare", "bench"}) {
    CliRun r = run_cli(std::string(cmd) + " --help", dir);
    INFO(cmd);
    CHECK(r.rc == 0);
    CHECK(r.out.find("--method") != std::string::npos);
  }
  fs::remove_all(dir);
}

TEST_CASE("cli: a bad --method is a usage error", "[cli][fast]") {
  const fs::path dir = scratch_dir("fast_cli");
  check_usage_error("saliency in.obj -o out.ply --method quick", "--method", dir);
  check_usage_error("bench in.obj --method auto", "--method", dir);
  fs::remove_all(dir);
}

TEST_CASE("cli: saliency --method fast writes the map and says so", "[cli][fast]") {
  MESHSAL_REQUIRE_MESH(input, "bunny_3k.off");
  fs::path dir = scratch_dir("fast_cli");
  CliRun r = run_cli("saliency " + input + " -o " + (dir / "f.ply").string() + " --method fast --backend cpu", dir);
  INFO(r.err);
  REQUIRE(r.rc == 0);
  CHECK(r.out.find("method     fast") != std::string::npos);
  meshsal::LoadedMesh read = meshsal::read_mesh((dir / "f.ply").string());
  const meshsal::Mesh& m = read.mesh;
  meshsal::VertexProperties& props = read.properties;
  REQUIRE(props.count("quality") == 1);
  CHECK(props["quality"].size() == m.vertex_count());
  CliRun e = run_cli("saliency " + input + " -o " + (dir / "e.ply").string() + " --backend cpu", dir);
  REQUIRE(e.rc == 0);
  CHECK(e.out.find("method     fast") == std::string::npos);
  fs::remove_all(dir);
}

TEST_CASE("cli: bench --method fast --json reports the error against exact", "[cli][fast]") {
  MESHSAL_REQUIRE_MESH(input, "bunny_3k.off");
  fs::path dir = scratch_dir("fast_cli");
  CliRun r = run_cli("bench " + input + " --repeat 1 --json --method fast", dir);
  INFO(r.err);
  REQUIRE(r.rc == 0);
  CHECK(r.out.find("\"method\": \"fast\"") != std::string::npos);
  CHECK(r.out.find("\"exact_measured\": true") != std::string::npos);
  const size_t at = r.out.find("\"correlation\": ");
  REQUIRE(at != std::string::npos);
  const double corr = std::atof(r.out.c_str() + at + 15);
  CHECK(corr > 0.99);
  CHECK(corr <= 1.0);
  CHECK(r.out.find("\"raw_max_rel\": [") != std::string::npos);
  CHECK(r.out.find("\"peak_rss_bytes\": ") != std::string::npos);
  fs::remove_all(dir);
}
