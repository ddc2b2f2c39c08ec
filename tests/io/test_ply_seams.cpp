// PLY files store a UV seam as vertices split at one position (find_seam_twins): loading
// with attributes finds them, simplification keeps such a seam closed as it does an OBJ's,
// and every command's saliency sees one surface there.
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "meshsal/meshsal.h"
#include "cli/synthetic.h"
#include "core/welded_view.h"
#include "io/seam_twins.h"
#include "cli_run.h"
#include "test_io_util.h"
#include "test_simplify_attributes_util.h"
#include "test_simplify_util.h"

using namespace meshsal;

namespace {

Mesh load_ply_text(const std::string& text, bool attributes) {
  LoadOptions o;
  o.attributes = attributes;
  return load_mesh_bytes(text, "seam.ply", o);
}

// Two triangles over the unit square; vertex 4 sits where vertex 2 is, with u = `u4`.
std::string quad_ply(float u4) {
  return "ply\nformat ascii 1.0\nelement vertex 5\nproperty float x\nproperty float y\n"
         "property float z\nproperty float u\nelement face 2\nproperty list uchar int vertex_indices\n"
         "end_header\n0 0 0 0\n1 0 0 1\n1 1 0 1\n0 1 -0 0\n1 1 0 " +
         std::to_string(u4) + "\n3 0 1 2\n3 0 4 3\n";
}

}  // namespace

TEST_CASE("ply attributes: vertices split at one position with other values are seam twins", "[io][simplify]") {
  const Mesh split = load_ply_text(quad_ply(0.5f), true);
  CHECK(split.position_vertex == std::vector<uint32_t>{0, 1, 2, 3, 2});
  // The same values: a plain duplicate, left as the file has it.
  CHECK(load_ply_text(quad_ply(1.0f), true).position_vertex.empty());
  // Without attributes kept the seam is found all the same (the properties tell it from a
  // duplicate), so that every front end computes S on one surface; the properties are dropped.
  const Mesh plain = load_ply_text(quad_ply(0.5f), false);
  CHECK(plain.position_vertex == std::vector<uint32_t>{0, 1, 2, 3, 2});
  CHECK(plain.attributes.empty());
  // -0 is the same position as +0.
  const std::string negzero =
      "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
      "property float u\nelement face 2\nproperty list uchar int vertex_indices\nend_header\n"
      "0 0 0 0\n1 0 0 0\n0 1 0 0\n-0 0 0 1\n3 0 1 2\n3 3 2 1\n";
  CHECK(load_ply_text(negzero, true).position_vertex == std::vector<uint32_t>{0, 1, 2, 0});
}

TEST_CASE("simplify keeps a PLY's UV seam closed", "[simplify][io]") {
  // The seamed sphere as an exporter writes it: split vertices in a PLY with u, v, nx, ny, nz.
  LoadOptions lo;
  lo.attributes = true;
  const Mesh obj = load_mesh_bytes(attr_test::seamed_sphere_obj(make_sphere(1.0, 4)), "seamed.obj", lo);
  meshsal_test::TempDir dir;
  const std::string path = dir.file("seamed.ply");
  Mesh file = obj;
  file.position_vertex.clear();  // a PLY cannot say which vertices are twins
  write_ply(path, file, {});
  const Mesh in = load_mesh(path, lo);
  REQUIRE(in.vertex_count() == obj.vertex_count());
  CHECK(in.position_vertex == obj.position_vertex);  // found again from the positions alone

  SimplifyOptions o;
  o.target_faces = 1000;
  const Simplified s = simplify_mesh(in, o);
  const Mesh& out = s.mesh;
  const SimplifyReport& rep = s.report;
  CHECK(out.triangle_count() == 1000);
  const simplify_test::Topology topo = simplify_test::topology(position_welded(out));
  CHECK(topo.border_edges == 0);
  CHECK(topo.nonmanifold_edges == 0);
  size_t moved = 0;
  for (size_t i = 0; i < out.vertex_count(); ++i) {
    const uint32_t src = rep.vertex_origin[i];
    if (in.position_vertex[src] == src && out.position_vertex[i] == i) continue;  // not a twin
    for (int k = 0; k < 3; ++k) moved += out.positions[3 * i + k] != in.positions[3 * size_t(src) + k];
  }
  CHECK(moved == 0);

  // Taken as the file's vertices alone, the seam is a cut and simplification opens it: its
  // two sides no longer meet, even welded by position.
  Mesh torn = in;
  torn.position_vertex.clear();
  torn = simplify_mesh(torn, o).mesh;
  find_seam_twins(torn);
  CHECK(simplify_test::topology(position_welded(torn)).border_edges > 20);
}

TEST_CASE("cli saliency of a PLY with a UV seam: the seam does not cut the surface", "[cli][io]") {
  // The seamed sphere in a PLY (twins split at one position) and the same sphere unsplit.
  LoadOptions lo;
  lo.attributes = true;
  const Mesh sphere = make_sphere(1.0, 3);
  Mesh split = load_mesh_bytes(attr_test::seamed_sphere_obj(sphere), "seamed.obj", lo);
  const std::vector<uint32_t> pv = split.position_vertex;
  split.position_vertex.clear();
  meshsal_test::TempDir dir;
  write_ply(dir.file("split.ply"), split, {});
  write_ply(dir.file("plain.ply"), sphere, {});
  for (const char* name : {"split", "plain"}) {
    const meshsal_test::CliRun r = meshsal_test::run_cli(
        "saliency " + dir.file(std::string(name) + ".ply") + " -o " + dir.file(std::string(name) + "_s.ply") +
            " -q --backend cpu", dir);
    REQUIRE(r.rc == 0);
  }
  Mesh file_split = split;
  file_split.attributes.clear();
  const std::vector<double> s_split = load_saliency_ply(dir.file("split_s.ply"), file_split);
  const std::vector<double> s_plain = load_saliency_ply(dir.file("plain_s.ply"), sphere);
  REQUIRE(s_split.size() == pv.size());
  size_t differ = 0;
  for (size_t i = 0; i < pv.size(); ++i) differ += s_split[i] != s_plain[pv[i]];
  CHECK(differ == 0);
}

TEST_CASE("cli simplify of a seamed PLY with --saliency-from its saliency file", "[cli][simplify]") {
  LoadOptions lo;
  lo.attributes = true;
  // The sphere's vertices moved off their symmetric places: on the perfect sphere many
  // collapses cost exactly the same, and which one goes first would hang on the last bit of
  // S (the file holds S as float, the computed S is double).
  Mesh sphere = make_sphere(1.0, 3);
  for (size_t i = 0; i < sphere.positions.size(); ++i)
    sphere.positions[i] *= float(1 + 0.02 * std::sin(12.9898 * double(i)));
  Mesh split = load_mesh_bytes(attr_test::seamed_sphere_obj(sphere), "seamed.obj", lo);
  split.position_vertex.clear();
  meshsal_test::TempDir dir;
  const std::string in = dir.file("split.ply"), sal = dir.file("split_s.ply");
  write_ply(in, split, {});
  REQUIRE(meshsal_test::run_cli("saliency " + in + " -o " + sal + " -q --backend cpu", dir).rc == 0);
  // S from the file (one value per vertex of the PLY, twins included) gives the weights the
  // computed S gives, to the file's float precision...
  {
    const Mesh m = load_mesh(in, lo);  // with its seams welded, as the commands load it
    const std::vector<double> s_file = load_saliency_ply(sal, m);
    SaliencyOptions so;
    so.backend = Backend::Cpu;
    const SaliencyWeightOptions wo = weight_preset(Weighting::Saliency);
    const std::vector<double> w_file = simplification_weights(m, wo, so, s_file).weights;
    const std::vector<double> w_computed = simplification_weights(m, wo, so).weights;
    REQUIRE(w_file.size() == w_computed.size());
    double largest = 0;
    for (double w : w_computed) largest = std::max(largest, std::fabs(w));
    // A vertex whose Sm lies within float rounding of the alpha percentile may fall on the
    // other side of it (its weight then changes by lambda): a few such, no more.
    size_t apart = 0;
    for (size_t v = 0; v < w_file.size(); ++v) apart += std::fabs(w_file[v] - w_computed[v]) > 1e-6 * largest;
    INFO(apart << " of " << w_file.size() << " weights differ by more than 1e-6 of the largest, " << largest);
    CHECK(largest > 0);
    CHECK(apart * 100 <= w_file.size());
  }
  // ...and so the same output.
  const meshsal_test::CliRun from_file =
      meshsal_test::run_cli("simplify " + in + " --saliency-from " + sal + " --target-faces 300 -o " +
                                dir.file("a.ply") + " -q --weights saliency", dir);
  INFO(from_file.err);
  REQUIRE(from_file.rc == 0);
  // (the paper's weighting, whose threshold the file's float S meets as the computed S does)
  REQUIRE(meshsal_test::run_cli("simplify " + in + " --backend cpu --target-faces 300 -o " + dir.file("b.ply") +
                                    " -q --weights saliency",
                                dir).rc == 0);
  const Mesh a = load_mesh(dir.file("a.ply")), b = load_mesh(dir.file("b.ply"));
  CHECK(a.triangle_count() == 300);
  CHECK(a.triangles == b.triangles);
}
