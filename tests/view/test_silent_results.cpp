// Issue 21 (11, 13): results that used to be silently wrong now come with a refusal or a note:
// a viewpoint where nothing scores, negative saliency read from a file, PLY list properties
// a simplification drops, and a mesh beyond float precision.
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "cli_run.h"
#include "cli/synthetic.h"
#include "meshsal/meshsal.h"
#include "test_util.h"

using namespace meshsal;
using namespace meshsal_test;
namespace fs = std::filesystem;

namespace {

Mesh one_triangle() {
  Mesh m;
  m.positions = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  m.triangles = {0, 1, 2};
  return m;
}

// A saliency PLY for `mesh` with these qualities.
void write_saliency(const std::string& path, const Mesh& mesh, const std::vector<double>& q) {
  write_ply(path, mesh, {{"quality", &q}});
}

}  // namespace

TEST_CASE("viewpoint: when no view sees any score, the front view with a note, not a random start", "[view]") {
  const Mesh m = one_triangle();
  SaliencyOptions so;
  so.backend = Backend::Cpu;
  const std::vector<double> s = compute_saliency(m, so).saliency;
  CHECK(s == std::vector<double>(3, 0.0));
  for (uint64_t seed : {1, 2, 3}) {
    ViewpointOptions o;
    o.optimiser.seed = seed;
    const Viewpoint b = best_viewpoint(m, s, o);
    // The front: theta 0, at the band's latitude nearest the horizon (the default band's lowest).
    CHECK(b.view.theta == 0);
    CHECK(b.view.phi == Approx(kDefaultElevationMin * M_PI / 180).margin(1e-12));
    CHECK(b.U == 0);
    CHECK(b.note.find("no view sees any score") == 0);
  }
  // A score that some view sees: no note.
  const Viewpoint b = best_viewpoint(m, {1.0, 1.0, 1.0});
  CHECK(b.note.empty());
  CHECK(b.U > 0);
}

TEST_CASE("viewpoint: a negative score is refused, every command refuses negative saliency files", "[view][cli]") {
  const Mesh m = make_sphere(1.0, 2);
  std::vector<double> s(m.vertex_count(), 1.0);
  s[7] = -284.7;
  CHECK_THROWS_WITH(best_viewpoint(m, s), "score of vertex 7 is -284.700000: a view score (a saliency, |curvature|) is >= 0");
  const fs::path dir = scratch_dir("negative_saliency");
  const std::string in = (dir / "ball.obj").string(), sal = (dir / "sal.ply").string();
  write_obj(in, m);
  write_saliency(sal, m, s);
  const std::string refused = "the quality of vertex 7 is -284.700012, but a saliency is >= 0";  // as float
  for (const std::string& cmd :
       {"viewpoint " + quoted(in) + " --saliency-from " + quoted(sal),
        "compare " + quoted(in) + " " + quoted(in) + " --saliency-from " + quoted(sal),
        "render " + quoted(in) + " -o " + quoted((dir / "r.png").string()) + " --saliency-from " + quoted(sal),
        "simplify " + quoted(in) + " -o " + quoted((dir / "s.obj").string()) + " --ratio 0.5 --saliency-from " +
            quoted(sal)}) {
    INFO(cmd);
    const CliRun r = run_cli(cmd, dir);
    CHECK(r.rc == 1);
    CHECK(r.err.find(refused) != std::string::npos);
  }
  // viewpoint on one triangle: the note on stderr and in the JSON.
  const std::string tri = (dir / "tri.obj").string();
  write_obj(tri, one_triangle());
  const CliRun r = run_cli("viewpoint " + quoted(tri), dir);
  CHECK(r.rc == 0);
  CHECK(r.err.find("note: no view sees any score") != std::string::npos);
  CHECK(r.out.find("\"note\": \"no view sees any score") != std::string::npos);
}

TEST_CASE("simplify: what a PLY holds that the output cannot carry is named", "[simplify][cli][io]") {
  const fs::path dir = scratch_dir("ply_unread");
  const Mesh m = make_sphere(1.0, 2);
  // Vertex list property (per-vertex texture coordinates as a list), a face property, an edge element.
  std::string ply = "ply\nformat ascii 1.0\nelement vertex " + std::to_string(m.vertex_count()) +
                    "\nproperty float x\nproperty float y\nproperty float z\nproperty float quality\n"
                    "property list uchar float texcoord\nelement face " + std::to_string(m.triangle_count()) +
                    "\nproperty list uchar int vertex_indices\nproperty uchar flags\nelement edge 1\n"
                    "property int vertex1\nproperty int vertex2\nend_header\n";
  for (size_t v = 0; v < m.vertex_count(); ++v)
    ply += std::to_string(m.positions[3 * v]) + " " + std::to_string(m.positions[3 * v + 1]) + " " +
           std::to_string(m.positions[3 * v + 2]) + " 0.5 2 0.25 0.75\n";
  for (size_t t = 0; t < m.triangle_count(); ++t)
    ply += "3 " + std::to_string(m.triangles[3 * t]) + " " + std::to_string(m.triangles[3 * t + 1]) + " " +
           std::to_string(m.triangles[3 * t + 2]) + " 1\n";
  ply += "0 1\n";
  const std::string in = (dir / "in.ply").string();
  std::ofstream(in) << ply;
  LoadOptions lo;
  lo.attributes = true;
  const LoadedMesh read = read_mesh(in, lo);
  const Mesh& loaded = read.mesh;
  const LoadReport& report = read.report;
  CHECK(report.unread == std::vector<std::string>{"vertex list property 'texcoord'", "face property 'flags'", "element 'edge'"});
  REQUIRE(loaded.attributes.size() == 1);
  CHECK(loaded.attributes[0].name == "quality");
  const CliRun r = run_cli("simplify " + quoted(in) + " -o " + quoted((dir / "out.ply").string()) + " --ratio 0.5", dir);
  CHECK(r.rc == 0);
  CHECK(r.err.find("note: " + in + ": not carried to the output: vertex list "
                   "property 'texcoord', face property 'flags', element 'edge'\n") != std::string::npos);
}

TEST_CASE("precision: a mesh beyond float precision is named as such, not blamed on manifoldness", "[simplify][cli]") {
  CHECK(precision_warning(make_sphere(1.0, 3)).empty());
  // The sphere far from the origin (1e6 units: the float step there is 0.06, an edge 0.1).
  Mesh far = make_sphere(1.0, 3);
  for (size_t i = 0; i < far.positions.size(); i += 3) far.positions[i] += 1e6f;
  const std::string w = precision_warning(far);
  CHECK(w.find("float precision: coordinates reach 1e+06") == 0);
  // One vertex 1e15 away, joined to the rest by one triangle.
  Mesh m = make_sphere(1.0, 3);
  m.positions.insert(m.positions.end(), {1e15f, 0, 0});
  const uint32_t far_vertex = uint32_t(m.vertex_count() - 1);
  m.triangles.insert(m.triangles.end(), {m.triangles[1], m.triangles[0], far_vertex});
  CHECK(precision_warning(m).find("(vertex " + std::to_string(far_vertex) + " at 1e+15, 0, 0;") != std::string::npos);
  {
    // Two vertices as far, in different threads' shares of a large mesh: the first is named,
    // as a serial scan names it.
    Mesh big = m;
    big.positions.resize(3 * 700000, 0.0f);
    const uint32_t early = 300000, late = 650000;
    big.positions[3 * late + 1] = -1e15f;
    big.positions[3 * early + 2] = 1e15f;
    big.triangles.insert(big.triangles.end(), {big.triangles[0], late, early});
    const std::string named = precision_warning(big);
    INFO(named);
    CHECK(named.find("(vertex " + std::to_string(far_vertex) + " at 1e+15") != std::string::npos);
    big.positions[3 * far_vertex] = 1e14f;
    CHECK(precision_warning(big).find("(vertex " + std::to_string(early) + " at 0, 0, 1e+15") != std::string::npos);
  }
  SimplifyOptions opt;
  opt.target_faces = 10;
  const SimplifyReport rep = simplify_mesh(m, opt).report;
  CHECK(rep.warning == precision_warning(m));
  if (!rep.reached) {
    CHECK(rep.note.find("the positions are too coarse at float precision") != std::string::npos);
    CHECK(rep.note.find("manifold") == std::string::npos);
  }
  // The CLI says it once, from the saliency's notice.
  const fs::path dir = scratch_dir("precision");
  const std::string in = (dir / "far.obj").string();
  write_obj(in, m);
  const CliRun r = run_cli("simplify " + quoted(in) + " -o " + quoted((dir / "o.obj").string()) + " --target-faces 10", dir);
  CHECK(r.rc == 0);
  // Loaded, the mesh is local to its bounding box's centre (5e14): the sphere is 5e14 from it.
  CHECK(r.err.find("warning: float precision: coordinates reach 5e+14 (vertex 0 at -0.525731, 0.850651, 0;") !=
        std::string::npos);
  CHECK(r.err.find("no further collapse keeps the mesh manifold") == std::string::npos);
  // Real scans are far from the limit.
  for (const char* name : {"bunny_36k.obj", "lucy_50k.ply", "igea_134k.ply.gz"}) {
    const std::string path = shared_mesh(name);
    if (!path.empty()) CHECK(precision_warning(load_mesh(path)).empty());
  }
}
