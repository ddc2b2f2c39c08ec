// --saliency-from FILE must belong to the mesh: same vertex count and the same positions (to
// float precision). A saliency PLY of another mesh with the same vertex count is refused and
// the first vertex that differs is named, in the library and by every command that reads one.
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>

#include "meshsal/meshsal.h"
#include "simplify/saliency_weights.h"
#include "cli/synthetic.h"
#include "test_util.h"

namespace fs = std::filesystem;
using namespace meshsal;

namespace {

struct Dir {
  fs::path path = fs::temp_directory_path() / ("meshsal_salfrom_" + std::to_string(::getpid()));
  Dir() { fs::create_directories(path); }
  ~Dir() { fs::remove_all(path); }
  std::string operator/(const std::string& n) const { return (path / n).string(); }
};

// A saliency PLY for `mesh`: quality = x coordinate, clamped at 0.
std::string write_saliency_of(const Mesh& mesh, const std::string& path) {
  std::vector<double> q(mesh.vertex_count());
  for (size_t i = 0; i < q.size(); ++i) q[i] = std::max(0.0, double(mesh.positions[3 * i]));
  write_ply(path, mesh, {{"quality", &q}});
  return path;
}

int run_cli(const std::string& args, std::string* out) {
  const std::string cmd = std::string("'") + MESHSAL_CLI + "' " + args + " 2>&1 < /dev/null";
  FILE* p = popen(cmd.c_str(), "r");
  REQUIRE(p != nullptr);
  char buf[4096];
  size_t n;
  out->clear();
  while ((n = fread(buf, 1, sizeof buf, p)) > 0) out->append(buf, n);
  const int status = pclose(p);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

}  // namespace

TEST_CASE("load_saliency_ply refuses the saliency of another mesh with the same vertex count", "[saliency]") {
  Dir dir;
  const Mesh mesh = make_sphere(1.0, 2);
  Mesh moved = mesh;
  moved.positions[3 * 17 + 1] += 0.01f;  // one vertex elsewhere
  Mesh other = make_sphere(2.0, 2);       // same count, every vertex elsewhere
  Mesh rounded = mesh;                    // the same mesh written with ~7 digits: accepted
  for (float& x : rounded.positions) x = float(double(x) * (1 + 3e-8));

  const std::string own = write_saliency_of(mesh, dir / "own.ply");
  CHECK(load_saliency_ply(own, mesh).size() == mesh.vertex_count());
  CHECK(load_saliency_ply(write_saliency_of(rounded, dir / "rounded.ply"), mesh).size() == mesh.vertex_count());
  CHECK_THROWS_WITH(load_saliency_ply(write_saliency_of(moved, dir / "moved.ply"), mesh),
                    Catch::StartsWith("saliency file '" + dir / "moved.ply" +
                                      "' belongs to another mesh: vertex 17 is at ("));
  CHECK_THROWS_WITH(load_saliency_ply(write_saliency_of(other, dir / "other.ply"), mesh),
                    Catch::Contains("belongs to another mesh: vertex 0 is at"));
  CHECK_THROWS_WITH(load_saliency_ply(own, make_sphere(1.0, 1)), Catch::Contains("vertices but the mesh has"));
}

TEST_CASE("cli: --saliency-from of another mesh is refused by every command", "[cli]") {
  Dir dir;
  const Mesh mesh = make_sphere(1.0, 2);
  const std::string obj = dir / "m.obj";
  write_obj(obj, mesh);
  Mesh other = mesh;
  for (size_t v = 40; v < other.vertex_count(); ++v) other.positions[3 * v] *= 1.5f;
  const std::string sal = write_saliency_of(other, dir / "other_sal.ply");
  const std::string expected = "error: saliency file '" + sal + "' belongs to another mesh: vertex 40 is at (";
  std::string out;
  for (const std::string& args :
       {"simplify '" + obj + "' -o '" + (dir / "s.obj") + "' --ratio 0.5 --saliency-from '" + sal + "'",
        "viewpoint '" + obj + "' --backend cpu --resolution 32 --restarts 1 --saliency-from '" + sal + "'",
        "render '" + obj + "' -o '" + (dir / "r.png") + "' --backend cpu --saliency-from '" + sal + "'",
        "compare '" + obj + "' '" + obj + "' --samples 100 --saliency '" + sal + "'"}) {
    INFO(args);
    CHECK(run_cli(args, &out) == 1);
    INFO(out);
    CHECK(out.rfind(expected, 0) == 0);
  }
  CHECK_FALSE(fs::exists(dir / "s.obj"));
  CHECK_FALSE(fs::exists(dir / "r.png"));
}
