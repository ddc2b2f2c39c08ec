// The meshsal executable and its outputs: no command writes over one of its inputs (also
// through a symlink or a hard link), outputs are checked before any work, and numbers that
// make no sense are refused as usage errors naming the option and its range.
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "meshsal/meshsal.h"
#include "cli/synthetic.h"
#include "cli_run.h"
#include "test_util.h"

namespace fs = std::filesystem;

using meshsal_test::CliRun;
using meshsal_test::read_file;
using meshsal_test::run_cli_merged;

namespace {

struct Scratch {
  fs::path dir;
  explicit Scratch(const std::string& name) {
    dir = fs::temp_directory_path() / ("meshsal_cli_out_" + name + "_" + std::to_string(::getpid()));
    fs::remove_all(dir);
    fs::create_directories(dir);
  }
  ~Scratch() { fs::remove_all(dir); }
  std::string operator/(const std::string& name) const { return (dir / name).string(); }
};

std::string q(const std::string& s) { return "'" + s + "'"; }

}  // namespace

TEST_CASE("cli: no command writes over one of its inputs", "[cli]") {
  Scratch s("inputs");
  const meshsal::Mesh mesh = meshsal::make_sphere(1.0, 2);
  const std::string obj = s / "a.obj", off = s / "x.off", ply = s / "d.ply";
  meshsal::write_obj(obj, mesh);
  meshsal::write_ply(ply, mesh, {});
  {
    std::ofstream f(off);
    f << "OFF\n4 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";
  }
  const std::string sal = s / "sal.ply";
  REQUIRE(run_cli_merged("saliency " + q(obj) + " -o " + q(sal) + " -q --backend cpu").rc == 0);
  fs::create_symlink(obj, s / "link.obj");
  fs::create_hard_link(ply, s / "hard.ply");
  const std::string obj_bytes = read_file(obj), off_bytes = read_file(off), ply_bytes = read_file(ply),
                    sal_bytes = read_file(sal);

  struct Case {
    std::string args, named;
  };
  const std::vector<Case> cases = {
      {"saliency " + q(ply) + " -o " + q(ply) + " --backend cpu", ply},
      {"saliency " + q(s / "hard.ply") + " -o " + q(ply) + " --backend cpu", ply},
      {"simplify " + q(obj) + " -o " + q(obj) + " --ratio 0.5 --weights none", obj},
      {"simplify " + q(obj) + " -o " + q(s / "link.obj") + " --ratio 0.5 --weights none", s / "link.obj"},
      {"simplify " + q(obj) + " -o " + q(sal) + " --ratio 0.5 --saliency-from " + q(sal), sal},
      {"render " + q(off) + " -o " + q(off), off},
      {"viewpoint " + q(off) + " --map " + q(off) + " --backend cpu", off},
      {"viewpoint " + q(obj) + " -o " + q(s / "v.png") + " --map " + q(s / "v.png") + " --backend cpu",
       s / "v.png"},
  };
  for (const Case& c : cases) {
    INFO(c.args);
    const CliRun r = run_cli_merged(c.args);
    INFO(r.out);
    CHECK(r.rc == 1);
    CHECK(r.out.rfind("error: " + c.named + ": ", 0) == 0);
    CHECK(std::count(r.out.begin(), r.out.end(), '\n') == 1);
  }
  CHECK(read_file(obj) == obj_bytes);
  CHECK(fs::is_symlink(s / "link.obj"));
  CHECK(read_file(off) == off_bytes);
  CHECK(read_file(ply) == ply_bytes);
  CHECK(read_file(s / "hard.ply") == ply_bytes);
  CHECK(read_file(sal) == sal_bytes);
  CHECK_FALSE(fs::exists(s / "v.png"));
  const CliRun same_inode = run_cli_merged("saliency " + q(s / "hard.ply") + " -o " + q(ply) + " --backend cpu");
  CHECK(same_inode.out.find("is the input file") != std::string::npos);
}

TEST_CASE("cli: outputs are checked before any work", "[cli]") {
  // The input does not even exist: a command that looked at its output only after loading
  // (or after hours of saliency) would complain about the input instead.
  Scratch s("early");
  const std::string missing = q(s / "missing.obj");
  struct Case {
    std::string args, expected;
  };
  const std::vector<Case> cases = {
      {"saliency " + missing + " -o " + q(s / "no/such/o.ply"), s / "no/such/o.ply" + ": cannot write: folder '" + s / "no/such" + "' does not exist"},
      {"saliency " + missing + " -o " + q(s / "o.txt"), s / "o.txt" + ": -o must be a .ply, .gltf, .glb, .obj, .off or .stl file"},
      {"simplify " + missing + " -o " + q(s / "o.stlx") + " --ratio 0.5", s / "o.stlx" + ": -o must be a .ply, .gltf, .glb, .obj, .off or .stl file"},
      {"simplify " + missing + " -o " + q(s / "no/o.obj") + " --ratio 0.5", s / "no/o.obj" + ": cannot write: folder"},
      {"render " + missing + " -o " + q(s / "o.jpg"), s / "o.jpg" + ": -o must be a .png file"},
      {"render " + missing + " -o " + q(s / "no/o.png"), s / "no/o.png" + ": cannot write: folder"},
      {"viewpoint " + missing + " --map " + q(s / "m.jpg"), s / "m.jpg" + ": --map must be a .png file"},
      {"viewpoint " + missing + " -o " + q(s / "no/b.png"), s / "no/b.png" + ": cannot write: folder"},
      {"viewpoint " + missing + " -o " + q(s.dir.string()) + "/", s.dir.string() + "/: -o must be a .png file"},
  };
  for (const Case& c : cases) {
    INFO(c.args);
    const CliRun r = run_cli_merged(c.args);
    INFO(r.out);
    CHECK(r.rc == 1);
    CHECK(r.out.rfind("error: " + c.expected, 0) == 0);
  }
  // demo: a file where the folder should be is refused before the demo mesh is built.
  { std::ofstream(s / "plainfile") << "x"; }
  const CliRun demo = run_cli_merged("demo -o " + q(s / "plainfile") + " --subdivisions 5 --backend cpu");
  INFO(demo.out);
  CHECK(demo.rc == 1);
  CHECK(demo.out.rfind("error: " + s / "plainfile" + ": cannot create the output folder", 0) == 0);
  CHECK(demo.out.find("demo mesh") == std::string::npos);
}

TEST_CASE("cli: numbers that make no sense are refused with the option and its range", "[cli]") {
  Scratch s("numbers");
  const std::string obj = s / "t.obj";
  meshsal::write_obj(obj, meshsal::make_sphere(1.0, 1));
  const std::string sal = "saliency " + q(obj) + " -o " + q(s / "o.ply") + " --backend cpu ";
  const std::string simp = "simplify " + q(obj) + " -o " + q(s / "o.obj") + " --weights none ";
  const std::string view = "viewpoint " + q(obj) + " --backend cpu --score curvature ";
  const std::string render = "render " + q(obj) + " -o " + q(s / "o.png") + " --grey ";
  struct Case {
    std::string args, expected;
  };
  const std::vector<Case> cases = {
      {sal + "--scales 1e300", "error: --scales: must be a comma-separated list of numbers in (0, 100], got '1e300'"},
      {sal + "--scales 2,nan", "error: --scales: must be a comma-separated list of numbers in (0, 100]"},
      {sal + "--eps-frac nan", "error: --eps-frac: must be a finite number in (0, 0.1], got 'nan'"},
      {sal + "--eps-frac 0", "error: --eps-frac: must be a finite number in (0, 0.1], got '0'"},
      {sal + "--threads 5000", "error: --threads: must be a whole number in [0, 1024], got '5000'"},
      {sal + "--threads -1", "error: --threads: must be a whole number in [0, 1024], got '-1'"},
      {simp + "--ratio inf", "error: --ratio: must be a finite number in (0, 1], got 'inf'"},
      {simp + "--ratio 0", "error: --ratio: must be a finite number in (0, 1], got '0'"},
      {simp + "--target-faces 0", "error: --target-faces: must be a whole number in [1, 4000000000], got '0'"},
      {simp + "--ratio 0.5 --lambda nan", "error: --lambda: must be a finite number in [0, 1e+06], got 'nan'"},
      {simp + "--ratio 0.5 --alpha-percentile 101", "error: --alpha-percentile: must be a finite number in [0, 100]"},
      {simp + "--ratio 0.5 --eps-frac 1e-400", "error: --eps-frac: must be a finite number in (0, 0.1]"},
      {simp + "--ratio 0.5 --threads 99999", "error: --threads: must be a whole number in [0, 1024]"},
      {view + "--resolution 0", "error: --resolution: must be a whole number in [16, 8192], got '0'"},
      {view + "--restarts 0", "error: --restarts: must be a whole number in [1, 1000], got '0'"},
      {view + "--views -5", "error: --views: must be a whole number in [0, 1000000], got '-5'"},
      {view + "--depth-tol inf", "error: --depth-tol: must be a finite number in [0, 1000], got 'inf'"},
      {view + "--map-width 10", "error: --map-width: must be a whole number in [32, 8192], got '10'"},
      {render + "--theta nan", "error: --theta: must be a finite number in [-360, 360], got 'nan'"},
      {render + "--phi 91", "error: --phi: must be a finite number in [-90, 90], got '91'"},
      {render + "--size 100000", "error: --size: must be a whole number in [16, 8192], got '100000'"},
      {"compare " + q(obj) + " " + q(obj) + " --samples -1", "error: --samples: must be a whole number in [0, 100000000]"},
      {"compare " + q(obj) + " " + q(obj) + " --salient-fraction nan", "error: --salient-fraction: must be a finite number in (0, 1]"},
      {"demo -o " + q(s / "d") + " --subdivisions 9", "error: --subdivisions: must be a whole number in [5, 8], got '9'"},
      {"bench --repeat 0 " + q(obj), "error: --repeat: must be a whole number in [1, 1000], got '0'"},
      {"bench --threads 2000 " + q(obj), "error: --threads: must be a whole number in [0, 1024], got '2000'"},
  };
  for (const Case& c : cases) {
    INFO(c.args);
    const CliRun r = run_cli_merged(c.args);
    INFO(r.out);
    CHECK(r.rc == 2);
    CHECK(r.out.rfind(c.expected, 0) == 0);
  }
  CHECK_FALSE(fs::exists(s / "o.ply"));
  CHECK_FALSE(fs::exists(s / "o.obj"));
  CHECK_FALSE(fs::exists(s / "o.png"));
  // A combination the ranges alone allow: the widest Gaussian would exceed the mesh.
  const CliRun wide = run_cli_merged(sal + "--scales 100 --eps-frac 0.01");
  CHECK(wide.rc == 1);
  CHECK(wide.out.rfind("error: scales and eps-frac: the widest surround sigma", 0) == 0);
}
