// [cli] What the person at the terminal sees: unknown commands with a suggestion, usage
// errors (exit 2) against bad input (exit 1), the STL weld note and -q, simplify with a
// target at or above the face count, compare's --saliency-from.
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "cli/synthetic.h"
#include "meshsal/meshsal.h"
#include "test_io_util.h"
#include "cli_run.h"
#include "test_util.h"

namespace fs = std::filesystem;
using meshsal_test::put_bin;

using meshsal_test::CliRun;
using meshsal_test::read_file;
using meshsal_test::run_cli;

namespace {

std::string q(const std::string& s) { return "'" + s + "'"; }

// Binary STL of `mesh`, corners by value.
std::string binary_stl(const meshsal::Mesh& mesh) {
  std::string s(80, ' ');
  put_bin<uint32_t>(s, static_cast<uint32_t>(mesh.triangle_count()));
  for (size_t t = 0; t < mesh.triangle_count(); ++t) {
    for (int k = 0; k < 3; ++k) put_bin(s, 0.0f);
    for (int c = 0; c < 3; ++c)
      for (int k = 0; k < 3; ++k) put_bin(s, mesh.positions[3 * mesh.triangles[3 * t + c] + k]);
    put_bin<uint16_t>(s, 0);
  }
  return s;
}

}  // namespace

TEST_CASE("cli: an unknown command says so and suggests the nearest", "[cli]") {
  meshsal_test::TempDir dir;
  CliRun r = run_cli("salency x.obj", dir);
  CHECK(r.rc == 2);
  CHECK(r.err == "error: unknown command 'salency', did you mean 'saliency'? (see meshsal --help)\n");
  r = run_cli("simp", dir);
  CHECK(r.rc == 2);
  CHECK(r.err == "error: unknown command 'simp', did you mean 'simplify'? (see meshsal --help)\n");
  r = run_cli("viewpiont", dir);
  CHECK(r.err == "error: unknown command 'viewpiont', did you mean 'viewpoint'? (see meshsal --help)\n");
  r = run_cli("frobnicate", dir);
  CHECK(r.rc == 2);
  CHECK(r.err == "error: unknown command 'frobnicate' (see meshsal --help)\n");
}

TEST_CASE("cli: option combinations are usage errors (exit 2), bad files exit 1", "[cli]") {
  meshsal_test::TempDir dir;
  const std::string mesh = dir.write("tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  CliRun r = run_cli("simplify " + q(mesh) + " -o " + q(dir.file("o.obj")) + " --weights none", dir);
  CHECK(r.rc == 2);
  CHECK(r.err == "error: give --target-faces N, --ratio R or --target-error E (see --help)\n");
  r = run_cli("saliency " + q(mesh) + " -o " + q(dir.file("o.ply")) + " --backend fast", dir);
  CHECK(r.rc == 2);
  CHECK(r.err == "error: --backend must be auto, cpu or gpu, got 'fast' (see --help)\n");
  r = run_cli("saliency " + q(dir.write("bad.stl", "solid x\nfacet facet\n")) + " -o " + q(dir.file("o.ply")), dir);
  CHECK(r.rc == 1);
  CHECK(r.err == "error: " + dir.file("bad.stl") + ": line 2: expected 'normal', found 'facet'\n");
}

TEST_CASE("cli: STL input is welded with a note that -q silences", "[cli][stl]") {
  meshsal_test::TempDir dir;
  const std::string stl = dir.write("sphere.stl", binary_stl(meshsal::make_sphere(1.0, 2)));
  const std::string out = dir.file("sphere_saliency.ply");
  CliRun r = run_cli("saliency " + q(stl) + " -o " + q(out) + " --backend cpu", dir);
  INFO(r.err);
  REQUIRE(r.rc == 0);
  CHECK(r.err == "note: " + stl + ": welded 798 STL corners into 162 shared vertices\n");
  const meshsal::Mesh welded = meshsal::load_mesh(out);
  CHECK(welded.vertex_count() == 162);
  CHECK(welded.triangle_count() == 320);
  r = run_cli("saliency " + q(stl) + " -o " + q(out) + " --backend cpu -q", dir);
  CHECK(r.rc == 0);
  CHECK(r.err.empty());
  CHECK(r.out.empty());
}

TEST_CASE("cli simplify: a target at or above the face count writes the mesh unchanged", "[cli][simplify]") {
  meshsal_test::TempDir dir;
  const meshsal::Mesh sphere = meshsal::make_sphere(1.0, 1);  // 80 faces
  meshsal::write_ply(dir.file("in.ply"), sphere, {});
  for (const std::string target : {"--target-faces 80", "--target-faces 1000", "--ratio 1"}) {
    INFO(target);
    const std::string out = dir.file("out.obj");
    CliRun r = run_cli("simplify " + q(dir.file("in.ply")) + " -o " + q(out) + " --weights none " + target, dir);
    CHECK(r.rc == 0);
    CHECK(r.err.find("note: the target (" + std::string(target == "--target-faces 1000" ? "1000" : "80") +
                     " faces) is at or above the mesh's 80 faces: wrote it unchanged\n") == 0);
    const meshsal::Mesh m = meshsal::load_mesh(out);
    CHECK(m.positions == sphere.positions);
    CHECK(m.triangles == sphere.triangles);
    fs::remove(out);
  }
  CliRun r = run_cli("simplify " + q(dir.file("in.ply")) + " -o " + q(dir.file("o.obj")) + " --target-faces 80 -q", dir);
  CHECK(r.rc == 0);
  CHECK(r.err.empty());
  CHECK(r.out.empty());
}

TEST_CASE("cli compare: --saliency-from like the other commands", "[cli]") {
  meshsal_test::TempDir dir;
  meshsal::write_ply(dir.file("sphere.ply"), meshsal::make_sphere(1.0, 2), {});
  const std::string sal = dir.file("sal.ply");
  REQUIRE(run_cli("saliency " + q(dir.file("sphere.ply")) + " -o " + q(sal) + " --backend cpu -q", dir).rc == 0);
  REQUIRE(run_cli("simplify " + q(dir.file("sphere.ply")) + " -o " + q(dir.file("s.ply")) +
                      " --ratio 0.5 --saliency-from " + q(sal) + " -q", dir).rc == 0);
  CliRun r = run_cli("compare " + q(dir.file("sphere.ply")) + " " + q(dir.file("s.ply")) + " --saliency-from " + q(sal) +
                      " --samples 1000", dir);
  INFO(r.err);
  CHECK(r.rc == 0);
  CHECK(r.out.find("\"saliency_source\": \"" + sal + "\"") != std::string::npos);
}

// On a terminal (util-linux `script` gives the command one), viewpoint and compare show
// their stages on stderr like the other long commands; through a pipe they stay silent.
TEST_CASE("cli: viewpoint and compare show progress on a terminal", "[cli]") {
  if (std::system("command -v script > /dev/null 2>&1") != 0) {
    meshsal_test::skip_case("util-linux `script` is not installed");
    return;
  }
  meshsal_test::TempDir dir;
  meshsal::write_ply(dir.file("sphere.ply"), meshsal::make_bumpy_sphere(3), {});
  const std::string base = std::string("'") + MESHSAL_CLI + "' ";
  auto on_terminal = [&](const std::string& args) {
    const std::string log = dir.file("tty.txt");
    const std::string cmd = "script -qec \"" + base + args + " > /dev/null\" /dev/null < /dev/null > '" + log + "' 2>&1";
    REQUIRE(std::system(cmd.c_str()) == 0);
    return meshsal_test::read_file(log);
  };
  const std::string mesh = q(dir.file("sphere.ply"));
  std::string tty = on_terminal("viewpoint " + mesh + " --backend cpu --restarts 2 --resolution 64 --views 300");
  CHECK(tty.find("best view") != std::string::npos);
  CHECK(tty.find("view map") != std::string::npos);
  CHECK(tty.find("100%") != std::string::npos);
  tty = on_terminal("compare " + mesh + " " + mesh + " --backend cpu --samples 100");
  CHECK(tty.find("reading") != std::string::npos);
  CHECK(tty.find("comparing surfaces") != std::string::npos);
  // Not a terminal: nothing but the JSON.
  const CliRun r = run_cli("compare " + mesh + " " + mesh + " --backend cpu --samples 100", dir);
  CHECK(r.rc == 0);
  CHECK(r.err.empty());
}
