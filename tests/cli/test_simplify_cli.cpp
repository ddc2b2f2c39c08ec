// `meshsal simplify` and `meshsal compare` end to end, including the errors on bad input.
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <string>

#include "meshsal/meshsal.h"
#include "cli/synthetic.h"
#include "cli_run.h"
#include "test_util.h"

namespace fs = std::filesystem;

using meshsal_test::CliRun;
using meshsal_test::read_file;
using meshsal_test::scratch_dir;
using meshsal_test::run_cli_merged;

TEST_CASE("cli simplify: target counts, formats and the saliency PLY", "[simplify]") {
  MESHSAL_REQUIRE_MESH(bunny, "bunny_3k.off");
  const fs::path dir = scratch_dir("simplify_cli");
  const std::string obj = (dir / "plain.obj").string(), ply = (dir / "sal.ply").string();
  CliRun r = run_cli_merged("simplify '" + bunny + "' -o '" + obj + "' --target-faces 1000 --weights none");
  INFO(r.out);
  REQUIRE(r.rc == 0);
  CHECK(meshsal::load_mesh(obj).triangle_count() == 1000);

  const std::string sal = (dir / "bunny_sal.ply").string();
  REQUIRE(run_cli_merged("saliency '" + bunny + "' -o '" + sal + "' --backend cpu -q").rc == 0);
  r = run_cli_merged("simplify '" + bunny + "' -o '" + ply + "' --ratio 0.1 --saliency-from '" + sal + "'");
  REQUIRE(r.rc == 0);
  const meshsal::Mesh out = meshsal::load_mesh(ply);
  CHECK(out.triangle_count() == 698);  // 10% of 6966 is 697: odd, so one above on a closed mesh
  CHECK(r.out.find("even face count") != std::string::npos);

  r = run_cli_merged("compare '" + bunny + "' '" + ply + "' --saliency '" + sal + "' --samples 20000");
  REQUIRE(r.rc == 0);
  for (const char* key : {"\"hausdorff\": ", "\"rms\": ", "\"salient_error\": ", "\"simplified_faces\": 698"})
    CHECK(r.out.find(key) != std::string::npos);
  CHECK(r.out.front() == '{');
  fs::remove_all(dir);
}

TEST_CASE("cli simplify: bad input gets a clear error", "[simplify]") {
  MESHSAL_REQUIRE_MESH(bunny, "bunny_3k.off");
  MESHSAL_REQUIRE_MESH(spot, "spot_3k.obj");
  const fs::path dir = scratch_dir("simplify_cli");
  const std::string out = (dir / "out.obj").string();
  const std::string base = "simplify '" + bunny + "' -o '" + out + "' --weights none ";
  // Out-of-range numbers are usage errors (exit 2), the rest bad input (exit 1).
  struct Case { std::string args, message; int rc; };
  const Case cases[] = {
      {"--target-faces 0", "--target-faces: must be a whole number in [1, 4000000000]", 2},
      {"--target-faces -5", "--target-faces: must be a whole number in [1, 4000000000]", 2},
      {"--ratio 0", "--ratio: must be a finite number in (0, 1]", 2},
      {"--ratio 1.5", "--ratio: must be a finite number in (0, 1]", 2},
      {"", "give --target-faces N, --ratio R or --target-error E (see --help)", 2},
      {"--target-faces 10 --ratio 0.5", "give only one of --target-faces N and --ratio R", 2},
      {"--target-error 0", "--target-error: must be a finite number in (0, 100]", 2},
      {"--target-error 101", "--target-error: must be a finite number in (0, 100]", 2},
      {"--target-error nan", "--target-error: must be a finite number in (0, 100]", 2},
  };
  for (const Case& c : cases) {
    const CliRun r = run_cli_merged(base + c.args);
    INFO(c.args << "\n" << r.out);
    CHECK(r.rc == c.rc);
    CHECK(r.out.find("error: ") != std::string::npos);
    CHECK(r.out.find(c.message) != std::string::npos);
  }
  // A saliency PLY of another mesh.
  const std::string sal = (dir / "spot_sal.ply").string();
  REQUIRE(run_cli_merged("saliency '" + spot + "' -o '" + sal + "' --backend cpu -q").rc == 0);
  CliRun r = run_cli_merged("simplify '" + bunny + "' -o '" + out + "' --target-faces 500 --saliency-from '" + sal + "'");
  INFO(r.out);
  CHECK(r.rc == 1);
  CHECK(r.out.find("has 2930 vertices but the mesh has 3485") != std::string::npos);
  r = run_cli_merged("compare '" + bunny + "' '" + spot + "' --saliency '" + sal + "'");
  CHECK(r.rc == 1);
  CHECK(r.out.find("has 2930 vertices but the mesh has 3485") != std::string::npos);
  // Every format the loaders read is written too: a binary STL of the 500 faces.
  r = run_cli_merged("simplify '" + bunny + "' -o '" + (dir / "x.stl").string() + "' --target-faces 500 -q");
  CHECK(r.rc == 0);
  CHECK(fs::file_size(dir / "x.stl") == 84 + 50 * 500);
  r = run_cli_merged("simplify '" + bunny + "' -o '" + (dir / "x.txt").string() + "' --target-faces 500");
  CHECK(r.rc == 1);
  CHECK(r.out.find("x.txt: -o must be a .ply, .gltf, .glb, .obj, .off or .stl file") != std::string::npos);
  CHECK_FALSE(fs::exists(out));
  fs::remove_all(dir);
}
