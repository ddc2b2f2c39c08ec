// One mesh document, every format: the table of attribute roles and of what each format
// keeps, the note naming what a write loses, the OFF and STL writers, vertex colours in
// OBJ and OFF both ways, and S read back from every format that keeps its value.
#include <filesystem>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "cli/synthetic.h"
#include "meshsal/meshsal.h"
#include "test_io_util.h"

using namespace meshsal;
using meshsal_test::read_file;
using meshsal_test::TempDir;

namespace {

std::vector<float> attr(const Mesh& mesh, const std::string& name) {
  for (const VertexAttribute& a : mesh.attributes)
    if (a.name == name) return a.values;
  return {};
}

Mesh with_attributes(const std::string& path) {
  LoadOptions o;
  o.attributes = true;
  return load_mesh(path, o);
}

// A small mesh with a colour per vertex (red = 10 v, green 200, blue 255 - 10 v).
Mesh coloured_quad() {
  Mesh m = make_mesh(std::vector<double>{0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0.5}.data(), 4,
                     std::vector<uint32_t>{0, 1, 2, 0, 2, 3}.data(), 6);
  m.attributes = {{"red", {0, 10, 20, 30}}, {"green", {200, 200, 200, 200}}, {"blue", {255, 245, 235, 225}}};
  return m;
}

}  // namespace

TEST_CASE("mesh formats: attribute roles, one table for every reader and writer", "[io][formats]") {
  CHECK(attribute_role("nz").kind == AttributeKind::Normal);
  CHECK(attribute_role("nz").component == 2);
  CHECK(attribute_role("u").kind == AttributeKind::TexCoord);
  CHECK(attribute_role("texture_v").component == 1);
  CHECK(attribute_role("t").set == 0);
  CHECK(attribute_role("u3").set == 3);
  CHECK(attribute_role("v7").component == 1);
  CHECK(attribute_role("u8").kind == AttributeKind::Scalar);
  CHECK(attribute_role("alpha").kind == AttributeKind::Color);
  CHECK(attribute_role("alpha").component == 3);
  CHECK(attribute_role(kSaliencyAttribute).kind == AttributeKind::Saliency);
  CHECK(attribute_role("curvature").kind == AttributeKind::Scalar);
}

TEST_CASE("mesh formats: the table of what each format keeps, and the suffix rule", "[io][formats]") {
  std::vector<std::string> suffixes;
  for (const MeshFormat& f : mesh_formats()) suffixes.push_back(f.suffix);
  CHECK(suffixes == std::vector<std::string>{".ply", ".gltf", ".glb", ".obj", ".off", ".stl"});
  CHECK(mesh_output_format("a/B.OFF") == ".off");
  CHECK(mesh_output_format("x.stl") == ".stl");
  CHECK(mesh_output_format("x.ply.gz") == "");
  CHECK(mesh_format("x.obj")->saliency == SaliencyKept::Colors);
  CHECK(mesh_format("x.stl")->saliency == SaliencyKept::None);
  CHECK(mesh_format("x.glb")->texcoord_sets == 8);
  CHECK(mesh_format("x.obj")->texcoord_sets == 1);
}

TEST_CASE("mesh formats: the note names once what a write loses", "[io][formats]") {
  Mesh m = coloured_quad();
  m.attributes.push_back({"u", {0, 1, 1, 0}});
  m.attributes.push_back({"v", {0, 0, 1, 1}});
  m.attributes.push_back({"u1", {0, 1, 1, 0}});
  m.attributes.push_back({"v1", {0, 0, 1, 1}});
  m.attributes.push_back({"curvature", {1, 2, 3, 4}});
  m.attributes.push_back({"nx", {0, 0, 0, 0}});
  CHECK(mesh_output_note("a.ply", m, true) == "");
  CHECK(mesh_output_note("a.glb", m, true) == "");
  CHECK(mesh_output_note("a.obj", m, true) ==
        "a.obj keeps S as vertex colours only, and has no place for texture coordinates of set 1 and the attribute "
        "'curvature' (.ply, .gltf and .glb keep every attribute)");
  CHECK(mesh_output_note("a.off", m, false) ==
        "a.off has no place for texture coordinates, the attribute 'curvature' and normals (.ply, .gltf and .glb keep every attribute)");
  CHECK(mesh_output_note("a.stl", m, true) ==
        "a.stl keeps no saliency, and has no place for vertex colours, texture coordinates, the attribute 'curvature' and "
        "normals (.ply, .gltf and .glb keep every attribute)");
  m.triangle_material = {0, 0};
  m.materials = {"skin"};
  CHECK_THAT(mesh_output_note("a.ply", m, false), Catch::Contains("no place for materials"));
  CHECK_THROWS_WITH(mesh_output_note("a.xyz", m, false), Catch::Contains("unknown mesh format"));
}

TEST_CASE("mesh formats: OFF and STL are written and read back, S goes where it fits or is refused", "[io][formats]") {
  TempDir dir;
  const Mesh sphere = make_bumpy_sphere(2);
  for (const char* name : {"s.off", "s.stl"}) {
    write_mesh(dir.file(name), sphere);
    const Mesh back = load_mesh(dir.file(name));
    REQUIRE(back.triangle_count() == sphere.triangle_count());
    // STL welds its corners back into the same vertices, in order of first use.
    const std::vector<double> a = model_positions(back);
    if (std::string(name) == "s.off") {
      // The coordinates as the OBJ writer gives them (the same text rule).
      write_mesh(dir.file("s.obj"), sphere);
      CHECK(back.triangles == sphere.triangles);
      CHECK(a == model_positions(load_mesh(dir.file("s.obj"))));
    }
  }
  // A binary STL: 84 + 50 bytes a triangle, its header never "solid".
  CHECK(std::filesystem::file_size(dir.file("s.stl")) == 84 + 50 * sphere.triangle_count());
  const std::vector<double> s(sphere.vertex_count(), 0.5);
  CHECK_THROWS_WITH(write_mesh(dir.file("x.stl"), sphere, s),
                    Catch::Contains("x.stl: cannot write: STL has no place for saliency (.ply, .gltf and .glb keep its values"));
  CHECK_FALSE(std::filesystem::exists(dir.file("x.stl")));
}

TEST_CASE("mesh formats: vertex colours in OBJ (v x y z r g b) and COFF, both ways, byte for byte", "[io][formats]") {
  TempDir dir;
  const Mesh m = coloured_quad();
  for (const char* name : {"c.obj", "c.off"}) {
    write_mesh(dir.file(name), m);
    const Mesh back = with_attributes(dir.file(name));
    CHECK(attr(back, "red") == attr(m, "red"));
    CHECK(attr(back, "green") == attr(m, "green"));
    CHECK(attr(back, "blue") == attr(m, "blue"));
    CHECK(model_positions(back) == model_positions(m));
  }
  CHECK(read_file(dir.file("c.obj")).find("\nv 1 0 0 0.039215688 0.78431374 0.9607843\n") != std::string::npos);
  CHECK(read_file(dir.file("c.off")).rfind("COFF\n", 0) == 0);
  // Without attributes the colours are not read (what saliency needs: positions only).
  CHECK(load_mesh(dir.file("c.off")).attributes.empty());
  // S written as colours: the pictures' scale, lowest blue, highest dark red.
  const std::vector<double> s{0, 1, 2, 3};
  write_mesh(dir.file("s.obj"), m, s);
  const Mesh back = with_attributes(dir.file("s.obj"));
  CHECK(attr(back, "red") == std::vector<float>{73, attr(back, "red")[1], attr(back, "red")[2], 155});
  CHECK(attr(back, "blue")[0] == 221);
}

TEST_CASE("mesh formats: COFF and NOFF columns as other writers put them", "[io][formats]") {
  // Integer colours with alpha; fractions; normals before colours; texture coordinates last.
  const std::string ints = "COFF\n3 1 0\n0 0 0 255 0 0 255\n1 0 0 0 255 0 128\n0 1 0 0 0 255 0\n3 0 1 2\n";
  const std::string fractions = "COFF\n3 1 0\n0 0 0 1 0 0\n1 0 0 0 1.0 0\n0 1 0 0 0 0.5\n3 0 1 2\n";
  const std::string both =
      "CNSTOFF\n3 1 0\n0 0 0 0 0 1 255 0 0 255 0.25 0.5\n1 0 0 0 0 1 0 255 0 255 1 0\n0 1 0 0 0 1 0 0 255 255 0 1\n3 0 1 2\n";
  LoadOptions o;
  o.attributes = true;
  const Mesh a = load_mesh_bytes(ints, "a.off", o);
  CHECK(attr(a, "red") == std::vector<float>{255, 0, 0});
  CHECK(attr(a, "alpha") == std::vector<float>{255, 128, 0});
  const Mesh b = load_mesh_bytes(fractions, "b.off", o);
  CHECK(attr(b, "green") == std::vector<float>{0, 255, 0});
  CHECK(attr(b, "blue") == std::vector<float>{0, 0, 128});
  CHECK(attr(b, "alpha") == std::vector<float>{255, 255, 255});
  const Mesh c = load_mesh_bytes(both, "c.off", o);
  CHECK(attr(c, "nz") == std::vector<float>{1, 1, 1});
  CHECK(attr(c, "red") == std::vector<float>{255, 0, 0});
  CHECK(attr(c, "u") == std::vector<float>{0.25f, 1, 0});
  CHECK(attr(c, "v") == std::vector<float>{0.5f, 0, 1});
  CHECK_THROWS_WITH(load_mesh_bytes("COFF\n3 1 0\n0 0 0 1 0\n1 0 0 0 1 0\n0 1 0 0 0 1\n3 0 1 2\n", "d.off", o),
                    Catch::Contains("d.off: line 3: vertex needs its colour"));
}

TEST_CASE("mesh formats: S read back from PLY and glTF alike, refused from a format without it", "[io][formats]") {
  TempDir dir;
  const Mesh sphere = make_bumpy_sphere(2);
  SaliencyOptions o;
  const std::vector<double> s = compute_saliency(sphere, o).saliency;
  for (const char* name : {"s.ply", "s.glb", "s.gltf"}) write_mesh(dir.file(name), sphere, s);
  const std::vector<double> from_ply = load_saliency(dir.file("s.ply"), sphere);
  CHECK(load_saliency(dir.file("s.glb"), sphere) == from_ply);
  CHECK(load_saliency(dir.file("s.gltf"), sphere) == from_ply);
  for (size_t v = 0; v < s.size(); ++v) CHECK(from_ply[v] == double(float(s[v])));
  write_mesh(dir.file("s.obj"), sphere, s);
  CHECK_THROWS_WITH(load_saliency(dir.file("s.obj"), sphere),
                    Catch::Contains("cannot hold saliency values (OBJ keeps S only as colours)"));
  write_mesh(dir.file("plain.glb"), sphere);
  CHECK_THROWS_WITH(load_saliency(dir.file("plain.glb"), sphere), Catch::Contains("has no per-vertex `quality` property"));
  CHECK_THROWS_WITH(load_saliency(dir.file("s.glb"), make_bumpy_sphere(1)), Catch::Contains("vertices but the mesh has"));
}
