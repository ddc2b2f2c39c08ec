// OBJ materials (mtllib, usemtl): read, written back, and carried through simplify_mesh,
// `meshsal simplify` and `meshsal batch --simplify`.
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "cli_run.h"
#include "meshsal/meshsal.h"
#include "test_io_util.h"

using namespace meshsal;
using namespace meshsal_test;
namespace fs = std::filesystem;

namespace {

constexpr int kN = 25;  // vertices per side of the grid

// A wavy (kN x kN)-vertex grid over [-1, 1]^2 with vt, two material libraries on one mtllib
// line and quads: the left half's (x < 0) under `usemtl left side` (a name with a blank),
// the right half's under `usemtl B`. `lead`: also two triangles before any usemtl.
std::string grid_obj(bool lead = false) {
  std::string s = "# test grid\nmtllib grid.mtl extra.mtl\n";
  auto coord = [](int i) { return -1.0 + 2.0 * i / (kN - 1); };
  for (int j = 0; j < kN; ++j)
    for (int i = 0; i < kN; ++i) {
      const double x = coord(i), y = coord(j), z = 0.15 * std::sin(3 * x) * std::cos(2 * y);
      s += "v " + std::to_string(x) + " " + std::to_string(y) + " " + std::to_string(z) + "\n";
    }
  for (int j = 0; j < kN; ++j)
    for (int i = 0; i < kN; ++i) s += "vt " + std::to_string(double(i) / (kN - 1)) + " " + std::to_string(double(j) / (kN - 1)) + "\n";
  auto id = [](int i, int j) { return std::to_string(j * kN + i + 1); };
  auto corner = [&](int i, int j) { return " " + id(i, j) + "/" + id(i, j); };
  if (lead) s += "f" + corner(0, 0) + corner(1, 0) + corner(0, 1) + "\nf" + corner(1, 0) + corner(1, 1) + corner(0, 1) + "\n";
  for (int half = 0; half < 2; ++half) {
    s += half == 0 ? "usemtl  left side \n" : "usemtl B\n";
    for (int j = 0; j + 1 < kN; ++j)
      for (int i = half == 0 ? 0 : (kN - 1) / 2; i < (half == 0 ? (kN - 1) / 2 : kN - 1); ++i) {
        if (lead && i == 0 && j == 0) continue;
        s += "f" + corner(i, j) + corner(i + 1, j) + corner(i + 1, j + 1) + corner(i, j + 1) + "\n";
      }
  }
  return s;
}

// Each triangle's centroid x in the model's coordinates.
std::vector<double> centroid_x(const Mesh& m) {
  std::vector<double> cx;
  const std::vector<double> p = model_positions(m);
  for (size_t t = 0; t < m.triangle_count(); ++t)
    cx.push_back((p[3 * m.triangles[3 * t]] + p[3 * m.triangles[3 * t + 1]] + p[3 * m.triangles[3 * t + 2]]) / 3);
  return cx;
}

// Every triangle of `m` (simplified from grid_obj) has the material of the half it lies in;
// a triangle at the middle line may lean over it by a collapse, never by much.
void check_halves(const Mesh& m) {
  REQUIRE(m.materials == std::vector<std::string>{"left side", "B"});
  REQUIRE(m.triangle_material.size() == m.triangle_count());
  const std::vector<double> cx = centroid_x(m);
  size_t left = 0, right = 0, leaning = 0;
  for (size_t t = 0; t < cx.size(); ++t) {
    INFO("triangle " << t << " centroid x " << cx[t] << " material " << m.triangle_material[t]);
    if (m.triangle_material[t] == 0) {
      ++left;
      CHECK(cx[t] < 0.2);
      leaning += cx[t] > 0;
    } else {
      ++right;
      CHECK(cx[t] > -0.2);
      leaning += cx[t] < 0;
    }
  }
  CHECK(left > 10);
  CHECK(right > 10);
  CHECK(leaning * 10 < cx.size());
}

size_t count(const std::string& text, const std::string& what) {
  size_t n = 0;
  for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

}  // namespace

TEST_CASE("OBJ materials: mtllib and usemtl are read, with or without attributes", "[materials]") {
  for (bool attributes : {false, true}) {
    INFO("attributes " << attributes);
    LoadOptions lo;
    lo.attributes = attributes;
    const Mesh m = load_mesh_bytes(grid_obj(), "grid.obj", lo);
    CHECK(m.material_libraries == std::vector<std::string>{"grid.mtl", "extra.mtl"});
    CHECK(m.materials == std::vector<std::string>{"left side", "B"});
    REQUIRE(m.triangle_material.size() == m.triangle_count());
    REQUIRE(m.triangle_count() == 2 * (kN - 1) * (kN - 1));
    // Quads: both fan triangles of a polygon take its material; the left half comes first.
    const size_t half = m.triangle_count() / 2;
    for (size_t t = 0; t < m.triangle_count(); ++t) CHECK(m.triangle_material[t] == (t < half ? 0u : 1u));
    const std::vector<double> cx = centroid_x(m);
    for (size_t t = 0; t < cx.size(); ++t) CHECK((cx[t] < 0) == (m.triangle_material[t] == 0));
  }
  // Faces before the first usemtl: the material "", after the named ones.
  const Mesh lead = load_mesh_bytes(grid_obj(true), "grid.obj");
  CHECK(lead.materials == std::vector<std::string>{"left side", "B", ""});
  CHECK(lead.triangle_material[0] == 2);
  CHECK(lead.triangle_material[1] == 2);
  CHECK(lead.triangle_material[2] == 0);
  // No usemtl: no materials (an mtllib alone is still kept).
  const Mesh plain = load_mesh_bytes("mtllib a.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", "plain.obj");
  CHECK(plain.material_libraries == std::vector<std::string>{"a.mtl"});
  CHECK(plain.materials.empty());
  CHECK(plain.triangle_material.empty());
}

TEST_CASE("OBJ materials: write_obj writes mtllib and usemtl back", "[materials]") {
  TempDir dir;
  LoadOptions lo;
  lo.attributes = true;
  const Mesh m = load_mesh_bytes(grid_obj(), "grid.obj", lo);
  write_obj(dir.file("out.obj"), m);
  const std::string text = read_file(dir.file("out.obj"));
  // The materials go into one library beside the output, named after it: here (the grid
  // came from memory, its libraries unread) an entry per material so that every usemtl
  // resolves.
  CHECK(text.rfind("# written by meshsal\nmtllib out.mtl\nv ", 0) == 0);
  CHECK(mesh_side_files(dir.file("out.obj"), m) == std::vector<std::string>{dir.file("out.mtl")});
  CHECK(read_file(dir.file("out.mtl")) ==
        "# written by meshsal from grid.mtl, extra.mtl\n\nnewmtl left side\n\nnewmtl B\n");
  CHECK(count(text, "usemtl left side\nf ") == 1);
  CHECK(count(text, "usemtl B\nf ") == 1);
  CHECK(count(text, "usemtl") == 2);
  const Mesh back = load_mesh(dir.file("out.obj"), lo);
  CHECK(back.material_libraries == std::vector<std::string>{"out.mtl"});
  CHECK(back.material_library_text == std::vector<std::string>{read_file(dir.file("out.mtl"))});
  CHECK(back.materials == m.materials);
  CHECK(back.triangle_material == m.triangle_material);
  CHECK(back.triangles == m.triangles);

  // Faces with no material first: no usemtl before them, and they read back as "".
  const Mesh lead = load_mesh_bytes(grid_obj(true), "grid.obj");
  write_obj(dir.file("lead.obj"), lead);
  const std::string lead_text = read_file(dir.file("lead.obj"));
  CHECK(count(lead_text, "usemtl") == 2);
  const Mesh lead_back = load_mesh(dir.file("lead.obj"));
  CHECK(lead_back.triangle_material == lead.triangle_material);
  CHECK(lead_back.materials == lead.materials);

  // "" after a named material: a bare usemtl, read back as "".
  Mesh hand = make_mesh(std::vector<float>{0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0}.data(), 4,
                        std::vector<uint32_t>{0, 1, 2, 1, 3, 2}.data(), 6);
  hand.materials = {"A", ""};
  hand.triangle_material = {0, 1};
  write_obj(dir.file("hand.obj"), hand);
  CHECK(read_file(dir.file("hand.obj")).find("usemtl A\nf 1 2 3\nusemtl\nf 2 4 3\n") != std::string::npos);
  const Mesh hand_back = load_mesh(dir.file("hand.obj"));
  CHECK(hand_back.materials == hand.materials);
  CHECK(hand_back.triangle_material == hand.triangle_material);

  // A mesh without materials: no mtllib, no usemtl.
  Mesh none = hand;
  none.materials.clear();
  none.triangle_material.clear();
  write_obj(dir.file("none.obj"), none);
  CHECK(read_file(dir.file("none.obj")).find("mtl") == std::string::npos);
  CHECK(mesh_side_files(dir.file("none.obj"), none).empty());
  CHECK_FALSE(fs::exists(dir.file("none.mtl")));

  // Wrong sizes or indices are refused by validate_mesh and write_obj.
  Mesh bad = hand;
  bad.triangle_material = {0, 2};
  CHECK_THROWS_AS(validate_mesh(bad), Error);
  CHECK_THROWS_AS(write_obj(dir.file("bad.obj"), bad), Error);
  bad.triangle_material = {0};
  CHECK_THROWS_AS(validate_mesh(bad), Error);
  CHECK_THROWS_AS(write_obj(dir.file("bad.obj"), bad), Error);
  CHECK_NOTHROW(validate_mesh(hand));
}

TEST_CASE("OBJ materials: simplify_mesh keeps each surviving triangle's material", "[materials]") {
  LoadOptions lo;
  lo.attributes = true;
  const Mesh m = load_mesh_bytes(grid_obj(), "grid.obj", lo);
  SimplifyOptions so;
  so.ratio = 0.2;
  const Mesh out = simplify_mesh(m, so).mesh;
  CHECK(out.triangle_count() < m.triangle_count() / 3);
  CHECK(out.material_libraries == m.material_libraries);
  check_halves(out);
  CHECK_NOTHROW(validate_mesh(out));
}

TEST_CASE("OBJ materials: meshsal simplify and batch --simplify keep the materials beside their outputs", "[materials][cli]") {
  const fs::path dir = scratch_dir("materials");
  fs::create_directories(dir / "in");
  const fs::path in = dir / "in" / "grid.obj";
  {
    std::ofstream f(in, std::ios::binary);
    f << grid_obj();
    std::ofstream(dir / "in" / "grid.mtl", std::ios::binary) << "newmtl left side\nKd 1 0 0\nmap_Kd wood.png\n";
    std::ofstream(dir / "in" / "extra.mtl", std::ios::binary) << "newmtl B\nKd 0 0 1\n";
  }
  const std::string library = "# written by meshsal from grid.mtl, extra.mtl\n\nnewmtl left side\nKd 1 0 0\nmap_Kd wood.png\n\nnewmtl B\nKd 0 0 1\n";
  LoadOptions lo;
  lo.attributes = true;

  // Beside the input: OUT.mtl holds the input's libraries; no note.
  CliRun r = run_cli("simplify " + quoted(in.string()) + " -o " + quoted((dir / "in" / "small.obj").string()) +
                         " --ratio 0.2 --backend cpu",
                     dir);
  REQUIRE(r.rc == 0);
  CHECK(r.err.find("material") == std::string::npos);
  CHECK(r.err.find("texture") == std::string::npos);
  std::string text = read_file((dir / "in" / "small.obj").string());
  CHECK(text.find("\nmtllib small.mtl\n") != std::string::npos);
  CHECK(read_file((dir / "in" / "small.mtl").string()) == library);
  CHECK(count(text, "usemtl left side\n") == 1);
  CHECK(count(text, "usemtl B\n") == 1);
  check_halves(load_mesh((dir / "in" / "small.obj").string(), lo));

  // Elsewhere: the same files, and a note to copy the texture the materials name.
  r = run_cli("simplify " + quoted(in.string()) + " -o " + quoted((dir / "small.obj").string()) +
                  " --ratio 0.2 --backend cpu",
              dir);
  REQUIRE(r.rc == 0);
  CHECK(r.err.find("names the input's textures wood.png relative to the input's folder") != std::string::npos);
  CHECK(read_file((dir / "small.obj").string()) == text);
  CHECK(read_file((dir / "small.mtl").string()) == library);

  // batch --simplify: the same mesh (simplify's options), the same materials.
  r = run_cli("batch " + quoted((dir / "in").string()) + " -o " + quoted((dir / "out").string()) +
                  " --backend cpu --simplify 0.2",
              dir);
  INFO(r.out << r.err);
  REQUIRE(r.rc == 0);
  CHECK(r.err.find("grid_simplified.obj names the input's textures wood.png relative to the input's folder") !=
        std::string::npos);
  const std::string batch_text = read_file((dir / "out" / "grid_simplified.obj").string());
  CHECK(count(batch_text, "mtllib grid_simplified.mtl\n") == 1);
  CHECK(read_file((dir / "out" / "grid_simplified.mtl").string()) == library);
  CHECK(count(batch_text, "usemtl left side\n") == 1);
  CHECK(count(batch_text, "usemtl B\n") == 1);
  CHECK(read_file((dir / "out" / "batch.jsonl").string()).find("wood.png") != std::string::npos);
  check_halves(load_mesh((dir / "out" / "grid_simplified.obj").string(), lo));
  fs::remove_all(dir);
}

TEST_CASE("OBJ materials: the input's libraries are read from its folder and written beside the output", "[materials]") {
  TempDir dir;
  fs::create_directories(dir.file("in"));
  fs::create_directories(dir.file("out"));
  const std::string lib = "# the grid's colours\nnewmtl left side\nKd 1 0 0\nmap_Kd wood.png\n";
  dir.write("in/grid.mtl", lib);  // extra.mtl is missing: named in the report, its material made plain
  dir.write("in/grid.obj", grid_obj());
  LoadOptions lo;
  lo.attributes = true;
  const LoadedMesh read = read_mesh(dir.file("in/grid.obj"), lo);
  const Mesh& m = read.mesh;
  const LoadReport& report = read.report;
  CHECK(m.material_library_text == std::vector<std::string>{lib, ""});
  CHECK(report.unread == std::vector<std::string>{"material library 'extra.mtl': no such file in the model's folder"});
  write_mesh(dir.file("out/small.obj"), m);
  CHECK(read_file(dir.file("out/small.mtl")) ==
        "# written by meshsal from grid.mtl, extra.mtl\n\n" + lib + "\n\nnewmtl B\n");
  // An output named like the input's library is refused before it replaces it.
  Mesh renamed = m;
  renamed.material_libraries = {"grid_copy.mtl"};
  dir.write("in/grid_copy.mtl", lib);
  CHECK_THROWS_WITH(write_mesh(dir.file("in/grid_copy.obj"), renamed), Catch::Contains("a material library of the input"));
  CHECK(read_file(dir.file("in/grid_copy.mtl")) == lib);
}

TEST_CASE("OBJ materials: a usemtl name that is not UTF-8 reaches a glTF output as its visible form", "[materials][cli]") {
  // glTF's JSON is UTF-8: the writer threw "[json.exception.type_error.316] invalid UTF-8
  // byte" and every .glb/.gltf output of such an OBJ failed.
  const fs::path dir = scratch_dir("materials_latin1");
  const fs::path in = dir / "m.obj";
  {
    std::ofstream f(in, std::ios::binary);
    f << "v 1 0 0\nv -1 0 0\nv 0 1 0\nv 0 -1 0\nv 0 0 1\nv 0 0 -1\n"
         "usemtl caf\xe9\nf 1 3 5\nf 3 2 5\nf 2 4 5\nf 4 1 5\n"
         "usemtl B \xe2\x80\xae ok\nf 3 1 6\nf 2 3 6\nf 4 2 6\nf 1 4 6\n";
  }
  for (const std::string out : {"s.glb", "s.gltf"}) {
    const CliRun r = run_cli("saliency " + quoted(in.string()) + " -o " + quoted((dir / out).string()) + " --backend cpu", dir);
    INFO(r.err);
    REQUIRE(r.rc == 0);
    const Mesh back = load_mesh((dir / out).string());
    REQUIRE(back.materials.size() == 2);
    CHECK(back.materials[0] == "caf\\xe9");
    CHECK(back.materials[1] == "B \xe2\x80\xae ok");  // valid UTF-8: the name as it is
  }
}
