// `meshsal simplify` with attributes, --target-error and --lock-border, end to end.
#include <sys/wait.h>

#include <cmath>
#include <cstdio>
#include <set>
#include <string>

#include "meshsal/meshsal.h"
#include "cli/synthetic.h"
#include "test_io_util.h"
#include "test_simplify_attributes_util.h"
#include "cli_run.h"
#include "test_util.h"

using namespace meshsal;

using meshsal_test::CliRun;
using meshsal_test::read_file;
using meshsal_test::run_cli_merged;

namespace {

std::string q(const std::string& s) { return "'" + s + "'"; }

}  // namespace

TEST_CASE("cli simplify: OBJ vt/vn and the saliency reach the output", "[simplify][cli]") {
  meshsal_test::TempDir dir;
  const std::string in = dir.write("seamed.obj", attr_test::seamed_sphere_obj(make_sphere(1.0, 3)));
  const std::string out_obj = dir.file("out.obj"), out_ply = dir.file("out.ply"), sal = dir.file("sal.ply");
  CliRun r = run_cli_merged("simplify " + q(in) + " -o " + q(out_obj) + " --target-faces 300 --weights none --json");
  INFO(r.out);
  REQUIRE(r.rc == 0);
  CHECK(r.out.find("\"attributes\": 5") != std::string::npos);
  CHECK(r.out.find("\"output_faces\": 300") != std::string::npos);
  const std::string text = meshsal_test::read_file(out_obj);
  CHECK(text.find("\nvt ") != std::string::npos);
  CHECK(text.find("\nvn ") != std::string::npos);
  CHECK(text.find("/") != std::string::npos);  // f v/vt/vn
  LoadOptions lo;
  lo.attributes = true;
  const Mesh back = load_mesh(out_obj, lo);
  CHECK(back.triangle_count() == 300);
  CHECK(back.attributes.size() == 5);
  CHECK_FALSE(back.position_vertex.empty());  // the seam is still there

  // The saliency of the positions (the OBJ read without vt/vn), reused; the PLY output
  // carries the attributes and S as `quality`.
  REQUIRE(run_cli_merged("saliency " + q(in) + " -o " + q(sal) + " --backend cpu -q").rc == 0);
  const VertexProperties sal_props = read_mesh(sal).properties;
  const std::vector<float>& s_in = sal_props.at("quality");
  r = run_cli_merged("simplify " + q(in) + " -o " + q(out_ply) + " --target-faces 300 --saliency-from " + q(sal));
  INFO(r.out);
  REQUIRE(r.rc == 0);
  CHECK(r.out.find("attributes u v nx ny nz quality") != std::string::npos);
  const LoadedMesh read = read_mesh(out_ply);
  const Mesh& ply = read.mesh;
  const VertexProperties& props = read.properties;
  CHECK(ply.triangle_count() == 300);
  for (const char* name : {"u", "v", "nx", "ny", "nz", "quality"}) CHECK(props.count(name) == 1);
  const std::vector<float>& s_out = props.at("quality");
  const std::set<float> given(s_in.begin(), s_in.end());
  size_t unmoved = 0;  // vertices no collapse moved keep their S exactly
  float lo_s = *given.begin(), hi_s = *given.rbegin(), lo_o = HUGE_VALF, hi_o = -HUGE_VALF;
  for (float x : s_out) {
    unmoved += given.count(x);
    lo_o = std::min(lo_o, x);
    hi_o = std::max(hi_o, x);
  }
  CHECK(unmoved > 20);  // the seam vertices alone are 46
  CHECK(lo_o >= lo_s);
  CHECK(hi_o <= hi_s);
  CHECK(hi_o > lo_o);
}

TEST_CASE("cli simplify: --target-error and --lock-border", "[simplify][cli]") {
  meshsal_test::TempDir dir;
  const std::string plane = dir.file("plane.ply"), out = dir.file("out.ply");
  write_ply(plane, make_plane(2.0, 12), {});
  CliRun r = run_cli_merged("simplify " + q(plane) + " -o " + q(out) + " --target-error 0.5 --weights none --json");
  INFO(r.out);
  REQUIRE(r.rc == 0);
  CHECK(r.out.find("\"output_faces\": 2,") != std::string::npos);
  CHECK(r.out.find("\"target_error_percent\": 0.5") != std::string::npos);
  CHECK(r.out.find("note:") == std::string::npos);  // no face target to miss

  const std::string bump = dir.file("bump.ply");
  const Mesh grid = make_plane_with_bump(2.0, 16, 0.3, 0.4);
  write_ply(bump, grid, {});
  r = run_cli_merged("simplify " + q(bump) + " -o " + q(out) + " --target-faces 100 --weights none --lock-border");
  INFO(r.out);
  REQUIRE(r.rc == 0);
  const Mesh m = load_mesh(out);
  CHECK(m.triangle_count() == 100);
  // All 64 border positions of the grid are still vertices.
  std::set<std::vector<float>> have;
  const std::vector<float> world = meshsal_test::world_floats(m);
  for (size_t i = 0; i < m.vertex_count(); ++i) have.insert({world[3 * i], world[3 * i + 1], world[3 * i + 2]});
  size_t border = 0, kept = 0;
  for (size_t i = 0; i < grid.vertex_count(); ++i) {
    const float* p = &grid.positions[3 * i];
    if (std::fabs(p[0]) < 0.999f && std::fabs(p[1]) < 0.999f) continue;
    ++border;
    kept += have.count({p[0], p[1], p[2]});
  }
  CHECK(border == 64);
  CHECK(kept == 64);
}
