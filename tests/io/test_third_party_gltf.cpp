// glTF files another tool made (glTF-Transform, npm @gltf-transform/core, run by
// web/make_gltf_scene.mjs in the test): a textured material and a plain one on one mesh,
// node transforms, an external .bin and image. Every output keeps what its format holds
// (the texture coordinates the textured material needs, the materials, the node frame)
// and every glTF written passes the Khronos validator.
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "cli_run.h"
#include "gltf_util.h"
#include "meshsal/meshsal.h"
#include "test_io_util.h"

using namespace meshsal;
namespace fs = std::filesystem;

namespace {

Mesh read(const std::string& path) {
  LoadOptions o;
  o.attributes = true;
  return load_mesh(path, o);
}

bool has(const Mesh& m, const std::string& name) {
  for (const VertexAttribute& a : m.attributes)
    if (a.name == name) return true;
  return false;
}

}  // namespace

TEST_CASE("third-party glTF: glTF-Transform's textured scene through saliency, simplify and LOD", "[gltf][cli][validator]") {
  const fs::path dir = meshsal_test::scratch_dir("third_party_gltf");
  const std::string make = "node '" + meshsal_test::web_tools_dir() + "/make_gltf_scene.mjs' '" + dir.string() + "'";
  REQUIRE(std::system(make.c_str()) == 0);
  const auto q = meshsal_test::quoted;
  for (const std::string in : {"scene.glb", "scene.gltf"}) {
    const std::string input = (dir / in).string();
    const Mesh source = read(input);
    REQUIRE(source.materials == std::vector<std::string>{"painted", "plain"});
    REQUIRE(source.frame.size() == 16);  // the nodes' transform, shared by the one instance
    for (const std::string out : {"glb", "gltf", "obj", "ply"}) {
      for (const std::string op : {"saliency", "simplify", "lod"}) {
        const std::string output = (dir / (in.substr(6) + "_" + op + "." + out)).string();
        const std::string args = op == "saliency" ? "saliency " + q(input) + " -o " + q(output)
                                 : op == "simplify" ? "simplify " + q(input) + " -o " + q(output) + " --ratio 0.3"
                                                    : "simplify " + q(input) + " -o " + q(output) + " --lod 0.3";
        const meshsal_test::CliRun r = meshsal_test::run_cli(args + " --backend cpu", dir);
        INFO(in << " -> " << out << " (" << op << "): " << r.err);
        REQUIRE(r.rc == 0);
        const std::string written = op == "lod" && (out == "obj" || out == "ply")
                                        ? output.substr(0, output.size() - out.size() - 1) + "_lod1." + out
                                        : output;
        const Mesh m = read(written);
        if (out == "glb" || out == "gltf") {
          // Materials, the UVs the texture needs, the node frame; nothing the validator refuses.
          CHECK(m.materials == source.materials);
          CHECK(has(m, "u"));
          CHECK(m.frame == source.frame);
          std::string report;
          INFO(report);
          CHECK(meshsal_test::validate_gltf(written, &report) == 0);
          CHECK(report.find(": 0 errors") != std::string::npos);
        } else if (out == "obj" && op != "saliency") {
          // The materials in MTL terms beside the OBJ, the texture written out as its own file.
          CHECK(m.materials == source.materials);
          CHECK(has(m, "u"));
          const std::string stem = written.substr(0, written.size() - 4);
          const std::string mtl = meshsal_test::read_file(stem + ".mtl");
          CHECK(mtl.find("newmtl painted\nKd 1 1 1\nmap_Kd " + fs::path(stem).filename().string() + "_tex0.png\n") !=
                std::string::npos);
          CHECK(mtl.find("newmtl plain\nKd 0.2 0.5 0.8\n") != std::string::npos);
          CHECK(meshsal_test::read_file(stem + "_tex0.png") == meshsal_test::read_file((dir / "texture.png").string()));
        } else if (out == "ply") {
          CHECK(r.err.find("materials") != std::string::npos);  // PLY has no place for them: said
        }
        // The model where the input put it: in world coordinates, the same box.
        if (op == "saliency") {
          const std::vector<double> a = model_positions(m), b = model_positions(source);
          REQUIRE(a.size() == b.size());
          for (size_t i = 0; i < a.size(); ++i) CHECK(a[i] == Approx(b[i]).margin(1e-5));
        }
      }
    }
  }
}
