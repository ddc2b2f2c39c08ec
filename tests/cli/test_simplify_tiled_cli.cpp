// `meshsal simplify --tiles N`: the tiled path from the command line, and its usage errors.
#include <filesystem>
#include <string>

#include "cli/synthetic.h"
#include "cli_run.h"
#include "json_check.h"
#include "meshsal/meshsal.h"
#include "test_util.h"

namespace fs = std::filesystem;
using namespace meshsal_test;

TEST_CASE("cli simplify --tiles: tiled output, reported in --json", "[simplify][tiled][cli]") {
  const fs::path dir = scratch_dir("simplify_tiles");
  const std::string in = (dir / "sphere.obj").string(), out = (dir / "out.obj").string();
  meshsal::write_obj(in, meshsal::make_sphere(1.0, 4));  // 5120 faces
  CliRun r = run_cli_merged("simplify " + quoted(in) + " -o " + quoted(out) + " --ratio 0.1 --weights none --tiles 4 --json");
  INFO(r.out);
  REQUIRE(r.rc == 0);
  CHECK(json_valid(r.out));
  CHECK(json_number(r.out, "tiles") == 4);
  CHECK(json_number(r.out, "target_faces") == 512);
  const double faces = json_number(r.out, "output_faces");
  CHECK(faces >= 512);
  CHECK(faces <= 512 * 1.01);
  CHECK(meshsal::load_mesh(out).triangle_count() == size_t(faces));
  // Without --tiles: one piece, as before.
  r = run_cli_merged("simplify " + quoted(in) + " -o " + quoted(out) + " --ratio 0.1 --weights none --json");
  REQUIRE(r.rc == 0);
  CHECK(json_number(r.out, "tiles") == 1);
  CHECK(json_number(r.out, "output_faces") == 512);
  fs::remove_all(dir);
}

TEST_CASE("cli simplify --tiles: bad values and combinations are usage errors", "[simplify][tiled][cli]") {
  const fs::path dir = scratch_dir("simplify_tiles_bad");
  const std::string in = (dir / "sphere.obj").string(), out = (dir / "out.obj").string();
  meshsal::write_obj(in, meshsal::make_sphere(1.0, 2));
  const std::string base = "simplify " + quoted(in) + " -o " + quoted(out) + " --weights none ";
  struct Case { std::string args, message; };
  const Case cases[] = {
      {"--ratio 0.5 --tiles 0", "--tiles: must be a whole number in [1, 1024]"},
      {"--ratio 0.5 --tiles -3", "--tiles: must be a whole number in [1, 1024]"},
      {"--ratio 0.5 --tiles 4x", "--tiles: must be a whole number in [1, 1024]"},
      {"--ratio 0.5 --tiles 100000", "--tiles: must be a whole number in [1, 1024]"},
      {"--target-error 1 --tiles 4", "--tiles takes --target-faces N or --ratio R, not --target-error"},
  };
  for (const Case& c : cases) {
    const CliRun r = run_cli_merged(base + c.args);
    INFO(c.args << "\n" << r.out);
    CHECK(r.rc == 2);
    CHECK(r.out.find(c.message) != std::string::npos);
    CHECK_FALSE(fs::exists(out));
  }
  const CliRun help = run_cli_merged("simplify --help");
  CHECK(help.out.find("--tiles") != std::string::npos);
  fs::remove_all(dir);
}
