// The command line with glTF: `saliency -o x.glb` (validator-clean, the PLY's saliency in
// _SALIENCY), a glTF input through `simplify` keeping its node transform and materials,
// and the outputs glTF cannot be.
#include <string>

#include <catch2/catch.hpp>

#include "cli/synthetic.h"
#include "cli_run.h"
#include "gltf_util.h"
#include "meshsal/meshsal.h"

using namespace meshsal;
using meshsal_test::quoted;
using meshsal_test::run_cli;
using meshsal_test::scratch_dir;

TEST_CASE("cli gltf: saliency -o x.glb holds the PLY's saliency, validator-clean", "[cli][gltf][validator]") {
  const auto dir = scratch_dir("cli_gltf");
  const std::string in = (dir / "m.obj").string();
  write_obj(in, make_bumpy_sphere(3));
  REQUIRE(run_cli("saliency " + quoted(in) + " -o " + quoted((dir / "m.ply").string()) + " -q --backend cpu", dir).rc == 0);
  REQUIRE(run_cli("saliency " + quoted(in) + " -o " + quoted((dir / "m.glb").string()) + " -q --backend cpu --dump-scales", dir).rc == 0);
  std::string report;
  INFO(report);
  CHECK(meshsal_test::validate_gltf((dir / "m.glb").string(), &report) == 0);
  // The GLB's _SALIENCY is the PLY's quality (both float).
  LoadOptions o;
  o.attributes = true;
  VertexProperties ply = read_mesh((dir / "m.ply").string()).properties;
  const LoadedMesh read = read_mesh((dir / "m.glb").string(), o);
  const Mesh& glb = read.mesh;
  const LoadReport& lr = read.report;
  CHECK(glb.vertex_count() == ply["quality"].size());
  // Every channel comes back: S (_SALIENCY) as the saliency attribute, the raw maps and
  // the curvature under their names; S read back from the GLB is the PLY's.
  CHECK(lr.unread.empty());
  std::vector<std::string> names;
  for (const VertexAttribute& a : glb.attributes) names.push_back(a.name);
  CHECK(names == std::vector<std::string>{"red", "green", "blue", "alpha", "quality", "curvature", "saliency_raw_0",
                                          "saliency_raw_1", "saliency_raw_2", "saliency_raw_3", "saliency_raw_4"});
  CHECK(load_saliency((dir / "m.glb").string(), glb) == load_saliency((dir / "m.ply").string(), glb));
  // The GLB read back gives the saliency of the PLY read back (both hold the model's
  // coordinates as floats), to the bit.
  for (const char* from : {"m.glb", "m.ply"})
    REQUIRE(run_cli("saliency " + quoted((dir / from).string()) + " -o " + quoted((dir / (std::string("again_") + from + ".ply")).string()) +
                        " -q --backend cpu",
                    dir).rc == 0);
  VertexProperties again_glb = read_mesh((dir / "again_m.glb.ply").string()).properties;
  VertexProperties again_ply = read_mesh((dir / "again_m.ply.ply").string()).properties;
  CHECK(again_glb["quality"] == again_ply["quality"]);
  // What glTF output does not go with.
  const auto r = run_cli("saliency " + quoted(in) + " -o " + quoted((dir / "x.glb").string()) + " --memory-limit 100M", dir);
  CHECK(r.rc == 2);
  CHECK(r.err.find("--memory-limit writes a binary PLY: give -o OUT.ply") != std::string::npos);
}

TEST_CASE("cli gltf: simplify glb -> glb keeps the node transform and the materials", "[cli][gltf][validator]") {
  const auto dir = scratch_dir("cli_gltf_simplify");
  // A two-material sphere under a node turned and moved, written by the library.
  Mesh m = make_bumpy_sphere(3);
  m.materials = {"skin", "eyes"};
  m.triangle_material.assign(m.triangle_count(), 0);
  for (size_t t = 0; t < m.triangle_count(); t += 7) m.triangle_material[t] = 1;
  std::vector<double> w = model_positions(m);
  for (size_t v = 0; v < m.vertex_count(); ++v) {
    const double x = w[3 * v], y = w[3 * v + 1];
    w[3 * v] = -y + 1000, w[3 * v + 1] = x, w[3 * v + 2] += 5;
  }
  set_model_positions(m, w.data(), m.vertex_count());
  m.frame = {0, 1, 0, 0, -1, 0, 0, 0, 0, 0, 1, 0, 1000, 0, 5, 1};
  const std::string in = (dir / "in.glb").string(), out = (dir / "out.glb").string();
  write_gltf(in, m);
  const auto r = run_cli("simplify " + quoted(in) + " -o " + quoted(out) + " --ratio 0.25 -q --backend cpu", dir);
  INFO(r.err);
  REQUIRE(r.rc == 0);
  std::string report;
  CHECK(meshsal_test::validate_gltf(out, &report) == 0);
  INFO(report);
  const Mesh s = load_mesh(out);
  CHECK(s.triangle_count() == m.triangle_count() / 4);
  REQUIRE(s.frame.size() == 16);
  CHECK(s.frame[12] == Approx(1000));
  CHECK(s.frame[4] == Approx(-1));
  CHECK(s.materials == std::vector<std::string>{"skin", "eyes"});
  CHECK(s.gltf_assets != nullptr);
}
