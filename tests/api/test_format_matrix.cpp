// The round-trip matrix (issue 37): each reader format x each writer format x {saliency,
// simplify, levels of detail}, and batch beside the CLI. What the input holds (normals,
// texture coordinates, colours, a scalar attribute, materials) either survives in the
// output or is named in the run's note; S is a value in PLY and glTF, colours in OBJ and
// OFF, refused for STL; every glTF written passes the Khronos validator; batch writes the
// command's bytes.
#include <cmath>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "cli/synthetic.h"
#include "cli_run.h"
#include "gltf_util.h"
#include "meshsal/meshsal.h"
#include "test_io_util.h"

using namespace meshsal;
namespace fs = std::filesystem;

namespace {

const std::vector<std::string> kFormats = {"ply", "gltf", "glb", "obj", "off", "stl"};

// What a file of one format, written from rich_mesh(), holds.
struct Holds {
  bool normals = false, uv = false, colours = false, scalar = false, materials = false;
};

Holds holds(const std::string& format) {
  if (format == "ply") return {true, true, true, true, false};
  if (format == "gltf" || format == "glb") return {true, true, true, true, true};
  if (format == "obj") return {true, true, true, false, true};
  if (format == "off") return {false, false, true, false, false};
  return {};
}

// A sphere with everything a mesh document carries: normals, texture coordinates, colours,
// a scalar `confidence`, and two materials (the upper and the lower half).
Mesh rich_mesh() {
  Mesh m = make_sphere(1.0, 2);
  const size_t n = m.vertex_count();
  const std::vector<double> p = model_positions(m);
  const char* names[] = {"nx", "ny", "nz", "u", "v", "red", "green", "blue", "alpha", "confidence"};
  for (const char* name : names) m.attributes.push_back({name, std::vector<float>(n)});
  for (size_t v = 0; v < n; ++v) {
    const double x = p[3 * v], y = p[3 * v + 1], z = p[3 * v + 2], r = std::sqrt(x * x + y * y + z * z);
    const float values[] = {float(x / r), float(y / r), float(z / r), float((x + 1) / 2), float((y + 1) / 2),
                            float(std::round(120 + 100 * x)), 200, float(std::round(120 + 100 * z)), 255, float(v % 7)};
    for (size_t k = 0; k < 10; ++k) m.attributes[k].values[v] = values[k];
  }
  m.materials = {"top", "bottom"};
  for (size_t t = 0; t < m.triangle_count(); ++t) {
    double cz = 0;
    for (int k = 0; k < 3; ++k) cz += p[3 * m.triangles[3 * t + size_t(k)] + 2];
    m.triangle_material.push_back(cz > 0 ? 0 : 1);
  }
  return m;
}

bool has(const Mesh& m, const std::string& name) {
  for (const VertexAttribute& a : m.attributes)
    if (a.name == name) return true;
  return false;
}

Mesh read(const std::string& path) {
  LoadOptions o;
  o.attributes = true;
  return load_mesh(path, o);
}

// Whether `kind` (a note's words) is named in what the run printed on stderr.
bool named(const std::string& err, const std::string& words) { return err.find(words) != std::string::npos; }

}  // namespace

TEST_CASE("format matrix: every reader x writer x saliency, simplify, LOD keeps or names", "[formats][cli][validator]") {
  const fs::path dir = meshsal_test::scratch_dir("format_matrix");
  const Mesh rich = rich_mesh();
  for (const std::string& f : kFormats) write_mesh((dir / ("in." + f)).string(), rich);
  std::vector<std::string> gltf_outputs;
  for (const std::string& in : kFormats) {
    const Holds h = holds(in);
    const std::string input = (dir / ("in." + in)).string();
    for (const std::string& out : kFormats) {
      const Holds keeps = holds(out);  // what the writer holds of a mesh document
      for (const std::string op : {"saliency", "simplify", "lod"}) {
        const std::string stem = (dir / (in + "_" + op + "_" + out)).string();
        const std::string output = stem + "." + out;
        const std::string args = op == "saliency" ? "saliency " + meshsal_test::quoted(input) + " -o " + meshsal_test::quoted(output)
                                 : op == "simplify" ? "simplify " + meshsal_test::quoted(input) + " -o " + meshsal_test::quoted(output) + " --ratio 0.5"
                                                    : "simplify " + meshsal_test::quoted(input) + " -o " + meshsal_test::quoted(output) + " --lod 0.5";
        const meshsal_test::CliRun r = meshsal_test::run_cli(args + " --backend cpu", dir);
        INFO(in << " -> " << out << " (" << op << "): " << r.err);
        if (op == "saliency" && out == "stl") {
          // STL keeps no S: refused before any work, naming the formats that do.
          CHECK(r.rc == 1);
          CHECK(named(r.err, "STL has no place for saliency (.ply, .gltf and .glb keep its values; .obj and .off its colours)"));
          continue;
        }
        REQUIRE(r.rc == 0);
        // The mesh written: LOD writes one glTF (the input as LOD0 in the scene) or a file per level.
        const bool lod_gltf = op == "lod" && (out == "glb" || out == "gltf");
        const std::string written = op == "lod" && !lod_gltf ? stem + "_lod1." + out : output;
        const Mesh m = read(written);
        if (op == "saliency" || lod_gltf) CHECK(m.triangle_count() == rich.triangle_count());
        else CHECK(m.triangle_count() < rich.triangle_count());
        if (out == "gltf" || out == "glb") gltf_outputs.push_back(written);
        // The saliency PLY holds positions, faces and S by definition (SPEC 4): the rest is named.
        const bool saliency_ply = op == "saliency" && out == "ply";
        const auto kept_or_named = [&](bool in_input, bool writer_keeps, bool present, const std::string& words) {
          if (!in_input) return;
          if (writer_keeps && !saliency_ply) CHECK(present);
          else CHECK(named(r.err, words));
        };
        kept_or_named(h.normals, keeps.normals, has(m, "nx"), "normals");
        kept_or_named(h.uv, keeps.uv, has(m, "u") && has(m, "v"), "texture coordinates");
        kept_or_named(h.scalar, keeps.scalar, has(m, "confidence"), "'confidence'");
        kept_or_named(h.materials, keeps.materials, m.materials == rich.materials, "materials");
        // Colours: the input's where S does not take their place.
        if (op != "saliency") kept_or_named(h.colours, keeps.colours, has(m, "red"), "vertex colours");
        // S: a value in PLY and glTF (the saliency, and what simplification carries), the
        // colours of its scale in OBJ and OFF.
        if (op == "saliency") {
          if (out == "ply" || out == "gltf" || out == "glb") {
            CHECK_NOTHROW(load_saliency(written, read(input)));
            CHECK(has(m, "red"));
          } else {
            CHECK(has(m, "red"));
            CHECK(named(r.err, "keeps S as vertex colours only"));
          }
        } else if (out == "ply" || out == "gltf" || out == "glb") {
          CHECK(has(m, kSaliencyAttribute));
        }
      }
    }
  }
  // Every glTF written, whatever it was read from: no validator error.
  for (const std::string& g : gltf_outputs) {
    std::string report;
    INFO(g << "\n" << report);
    CHECK(meshsal_test::validate_gltf(g, &report) == 0);
    CHECK(report.find(": 0 errors") != std::string::npos);
  }
}

TEST_CASE("format matrix: batch writes the command's bytes for every reader format", "[formats][cli][batch]") {
  const fs::path dir = meshsal_test::scratch_dir("format_matrix_batch");
  const Mesh rich = rich_mesh();
  for (const std::string& f : kFormats) {
    fs::create_directories(dir / f);
    write_mesh((dir / f / ("m." + f)).string(), rich);
    const std::string in = (dir / f / ("m." + f)).string();
    const auto q = meshsal_test::quoted;
    REQUIRE(meshsal_test::run_cli("batch " + q((dir / f).string()) + " -o " + q((dir / ("out_" + f)).string()) +
                                      " --simplify 0.5 --lod 0.5 --backend cpu -q",
                                  dir).rc == 0);
    REQUIRE(meshsal_test::run_cli("saliency " + q(in) + " -o " + q((dir / ("s_" + f + ".ply")).string()) + " --backend cpu -q", dir).rc == 0);
    REQUIRE(meshsal_test::run_cli("simplify " + q(in) + " -o " + q((dir / ("r_" + f + ".obj")).string()) +
                                      " --ratio 0.5 --backend cpu -q",
                                  dir).rc == 0);
    REQUIRE(meshsal_test::run_cli("simplify " + q(in) + " -o " + q((dir / ("l_" + f + ".glb")).string()) +
                                      " --lod 0.5 --backend cpu -q",
                                  dir).rc == 0);
    INFO(f);
    CHECK(meshsal_test::read_file((dir / ("out_" + f) / "m_saliency.ply").string()) ==
          meshsal_test::read_file((dir / ("s_" + f + ".ply")).string()));
    // The OBJ names its own .mtl (m_simplified.mtl beside it, r_F.mtl beside the other):
    // the same bytes once that name is the same.
    std::string batch_obj = meshsal_test::read_file((dir / ("out_" + f) / "m_simplified.obj").string());
    const std::string mtllib = "mtllib m_simplified.mtl\n";
    if (const size_t at = batch_obj.find(mtllib); at != std::string::npos)
      batch_obj.replace(at, mtllib.size(), "mtllib r_" + f + ".mtl\n");
    CHECK(batch_obj == meshsal_test::read_file((dir / ("r_" + f + ".obj")).string()));
    CHECK(meshsal_test::read_file((dir / ("out_" + f) / "m_lod.glb").string()) ==
          meshsal_test::read_file((dir / ("l_" + f + ".glb")).string()));
  }
}
