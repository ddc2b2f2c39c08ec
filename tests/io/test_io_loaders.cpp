// [io] loaders: the shared meshes load with their SOURCES.md counts, and small generated
// files exercise every supported OBJ / PLY / OFF form.
#include <zlib.h>
#include <cstring>
#include <vector>

#include "io/ply_stream.h"
#include "meshsal/meshsal.h"
#include "test_io_util.h"
#include "test_util.h"

using meshsal::Mesh;
using meshsal::VertexProperties;
using meshsal_test::put_bin;
using meshsal_test::TempDir;

namespace {

void check_counts(const std::string& path, size_t v, size_t t) {
  const Mesh m = meshsal::read_mesh(path).mesh;  // the properties read too
  CHECK(m.vertex_count() == v);
  CHECK(m.triangle_count() == t);
}

// The little test mesh used below in every format: 5 vertices, a quad and a triangle.
//   quad 0 1 2 3 -> (0 1 2) (0 2 3); triangle 1 4 2
const std::vector<float> kPos = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 2, 0.5f, 0.25f};
const std::vector<uint32_t> kTri = {0, 1, 2, 0, 2, 3, 1, 4, 2};

void check_small(const Mesh& m) {
  CHECK(meshsal_test::world_floats(m) == kPos);
  CHECK(m.triangles == kTri);
}

}  // namespace

// --- shared meshes: counts from SOURCES.md (F polygons; suzanne fans to 968 triangles) ---
TEST_CASE("load bunny_36k.obj", "[io]") { MESHSAL_REQUIRE_MESH(p, "bunny_36k.obj"); check_counts(p, 35947, 69451); }
TEST_CASE("load bun_zipper_res2.ply", "[io]") { MESHSAL_REQUIRE_MESH(p, "bun_zipper_res2.ply"); check_counts(p, 8171, 16301); }
TEST_CASE("load bunny_3k.off", "[io]") { MESHSAL_REQUIRE_MESH(p, "bunny_3k.off"); check_counts(p, 3485, 6966); }
TEST_CASE("load armadillo_43k.obj", "[io]") { MESHSAL_REQUIRE_MESH(p, "armadillo_43k.obj"); check_counts(p, 43243, 86482); }
TEST_CASE("load lucy_50k.ply", "[io]") { MESHSAL_REQUIRE_MESH(p, "lucy_50k.ply"); check_counts(p, 50002, 100000); }
TEST_CASE("load max_planck_5k.obj", "[io]") { MESHSAL_REQUIRE_MESH(p, "max_planck_5k.obj"); check_counts(p, 5272, 10540); }
TEST_CASE("load igea_134k.ply.gz", "[io]") { MESHSAL_REQUIRE_MESH(p, "igea_134k.ply.gz"); check_counts(p, 134345, 268686); }
TEST_CASE("load igea_loop1_537k.ply.gz", "[io]") { MESHSAL_REQUIRE_MESH(p, "igea_loop1_537k.ply.gz"); check_counts(p, 537374, 1074744); }
TEST_CASE("load dinosaur_14k.obj", "[io]") { MESHSAL_REQUIRE_MESH(p, "dinosaur_14k.obj"); check_counts(p, 14000, 27996); }
TEST_CASE("load fandisk_6k.obj", "[io]") { MESHSAL_REQUIRE_MESH(p, "fandisk_6k.obj"); check_counts(p, 6475, 12946); }
// Hidden (run with "[io-big]"): 49 MB gzip, about a second; kept out of the default run.
TEST_CASE("load igea_loop2_2149k.ply.gz", "[.][io-big]") {
  MESHSAL_REQUIRE_MESH(p, "igea_loop2_2149k.ply.gz");
  check_counts(p, 2149490, 4298976);
}

TEST_CASE("load bun_zipper_res3.ply: values and extra properties", "[io]") {
  MESHSAL_REQUIRE_MESH(p, "bun_zipper_res3.ply");
  meshsal::LoadedMesh read = meshsal::read_mesh(p);
  const Mesh& m = read.mesh;
  VertexProperties& props = read.properties;
  REQUIRE(m.vertex_count() == 1889);
  REQUIRE(m.triangle_count() == 3851);
  // First data line: -0.0369122 0.127512 0.00276757 0.850855 0.5
  CHECK(meshsal_test::world_floats(m)[0] == -0.0369122f);
  CHECK(meshsal_test::world_floats(m)[1] == 0.127512f);
  CHECK(meshsal_test::world_floats(m)[2] == 0.00276757f);
  REQUIRE(props.size() == 2);
  REQUIRE(props["confidence"].size() == 1889);
  REQUIRE(props["intensity"].size() == 1889);
  CHECK(props["confidence"][0] == 0.850855f);
  CHECK(props["intensity"][0] == 0.5f);
}

TEST_CASE("load dragon_50k.ply: binary with normals as extra properties", "[io]") {
  MESHSAL_REQUIRE_MESH(p, "dragon_50k.ply");
  meshsal::LoadedMesh read = meshsal::read_mesh(p);
  const Mesh& m = read.mesh;
  VertexProperties& props = read.properties;
  CHECK(m.vertex_count() == 50002);
  CHECK(m.triangle_count() == 100000);
  REQUIRE(props.size() == 3);
  REQUIRE(props.count("nx") == 1);
  REQUIRE(props["nz"].size() == 50002);
  // Normals are unit length.
  float len2 = props["nx"][7] * props["nx"][7] + props["ny"][7] * props["ny"][7] + props["nz"][7] * props["nz"][7];
  CHECK(len2 == Approx(1.0f).epsilon(1e-3));
}

TEST_CASE("load spot_3k.obj (f v/vt) and suzanne.obj (f v//vn, quads)", "[io]") {
  MESHSAL_REQUIRE_MESH(spot, "spot_3k.obj");
  check_counts(spot, 2930, 5856);
  MESHSAL_REQUIRE_MESH(suz, "suzanne.obj");
  Mesh m = meshsal::load_mesh(suz);
  CHECK(m.vertex_count() == 507);
  CHECK(m.triangle_count() == 968);  // 468 quads * 2 + 32 triangles
}

TEST_CASE("load OFF first vertex", "[io]") {
  MESHSAL_REQUIRE_MESH(p, "bunny_3k.off");
  Mesh m = meshsal::load_mesh(p);
  CHECK(meshsal_test::world_floats(m)[0] == -0.0260146f);
  CHECK(meshsal_test::world_floats(m)[5] == -0.00263321f);
}

// --- generated files -------------------------------------------------------------

TEST_CASE("OBJ forms: v/vt, v//vn, v/vt/vn, negative indices, polygons, comments", "[io]") {
  TempDir dir;
  const std::string obj =
      "# comment\r\n"
      "mtllib x.mtl\n"
      "o thing\n"
      "v 0 0 0\n"
      "v 1.0 0 0 1.0\n"       // optional w
      "v 1 1e0 0 0.5 0.5 0.5\n"  // vertex colour columns
      "vt 0 0\nvt 1 0\nvn 0 0 1\n"
      "v +0 1 -0  # trailing comment\n"
      "usemtl m\ns off\n"
      "f 1/1 2//1 3/2/1 4\n"
      "v 2 0.5 0.25\n"
      "g tail\n"
      "f -4 -1 -3\n";  // relative: vertices 2 5 3
  Mesh m = meshsal::load_mesh(dir.write("forms.obj", obj));
  check_small(m);
}

TEST_CASE("case-insensitive extensions and gzipped OBJ", "[io]") {
  TempDir dir;
  const std::string obj = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 2 0.5 0.25\nf 1 2 3 4\nf 2 5 3\n";
  check_small(meshsal::load_mesh(dir.write("upper.OBJ", obj)));
  check_small(meshsal::load_mesh(dir.write_gz("packed.obj.gz", obj)));
  check_small(meshsal::load_mesh(dir.write_gz("PACKED.Obj.GZ", obj)));
}

TEST_CASE("PLY ascii: comments, obj_info, CRLF, extra typed properties, other elements", "[io]") {
  TempDir dir;
  const std::string ply =
      "ply\r\n"
      "format ascii 1.0\r\n"
      "comment made by hand\r\n"
      "obj_info nothing\r\n"
      "element vertex 5\r\n"
      "property double x\r\nproperty double y\r\nproperty double z\r\n"
      "property uchar red\r\n"
      "property list uchar float junk\r\n"
      "property short q\r\n"
      "element face 2\r\n"
      "property uchar flags\r\n"
      "property list ushort uint vertex_index\r\n"
      "element edge 1\r\n"
      "property int vertex1\r\nproperty int vertex2\r\n"
      "end_header\r\n"
      "0 0 0 10 0 -1\r\n"
      "1 0 0 11 2 0.5 0.5 2\r\n"
      "1 1 0 12 1 7 3\r\n"
      "0 1 0 13 0 4\r\n"
      "2 0.5 0.25 255 0 -32768\r\n"
      "0 4 0 1 2 3\r\n"
      "9 3 1 4 2\r\n"
      "0 1\r\n";
  meshsal::LoadedMesh read = meshsal::read_mesh(dir.write("forms.ply", ply));
  const Mesh& m = read.mesh;
  VertexProperties& props = read.properties;
  check_small(m);
  REQUIRE(props.size() == 2);
  CHECK(props["red"] == std::vector<float>{10, 11, 12, 13, 255});
  CHECK(props["q"] == std::vector<float>{-1, 2, 3, 4, -32768});
}

namespace {

// The small mesh as binary PLY: double x/y/z, char / float extras, a vertex list to skip,
// a face element with a leading int property and int indices (uint count), a trailing
// material element.
std::string binary_ply(bool big) {
  std::string s = std::string("ply\nformat ") + (big ? "binary_big_endian" : "binary_little_endian") +
                  " 1.0\n"
                  "element vertex 5\n"
                  "property char tag\n"
                  "property double x\nproperty double y\nproperty double z\n"
                  "property list int short skipme\n"
                  "property float quality\n"
                  "element face 2\n"
                  "property int id\n"
                  "property list uint int vertex_indices\n"
                  "element material 2\n"
                  "property uchar r\nproperty list uchar uchar name\n"
                  "end_header\n";
  for (int v = 0; v < 5; ++v) {
    put_bin<int8_t>(s, static_cast<int8_t>(-v), big);
    for (int k = 0; k < 3; ++k) put_bin<double>(s, kPos[3 * v + k], big);
    put_bin<int32_t>(s, v % 3, big);  // list length 0..2
    for (int i = 0; i < v % 3; ++i) put_bin<int16_t>(s, 7, big);
    put_bin<float>(s, 0.5f * v, big);
  }
  put_bin<int32_t>(s, 100, big);
  put_bin<uint32_t>(s, 4, big);
  for (int i : {0, 1, 2, 3}) put_bin<int32_t>(s, i, big);
  put_bin<int32_t>(s, 101, big);
  put_bin<uint32_t>(s, 3, big);
  for (int i : {1, 4, 2}) put_bin<int32_t>(s, i, big);
  for (int k = 0; k < 2; ++k) {
    put_bin<uint8_t>(s, 9);
    put_bin<uint8_t>(s, 2);
    s += "ab";
  }
  return s;
}

}  // namespace

TEST_CASE("PLY binary little and big endian, skipped lists and elements", "[io]") {
  TempDir dir;
  for (bool big : {false, true}) {
    INFO((big ? "big endian" : "little endian"));
    meshsal::LoadedMesh read = meshsal::read_mesh(dir.write(big ? "be.ply" : "le.ply", binary_ply(big)));
    const Mesh& m = read.mesh;
    VertexProperties& props = read.properties;
    check_small(m);
    REQUIRE(props.size() == 2);
    CHECK(props["tag"] == std::vector<float>{0, -1, -2, -3, -4});
    CHECK(props["quality"] == std::vector<float>{0, 0.5f, 1, 1.5f, 2});
  }
  check_small(meshsal::load_mesh(dir.write_gz("le.PLY.gz", binary_ply(false))));
}

TEST_CASE("PLY read by load_mesh (no properties) ignores extras", "[io]") {
  TempDir dir;
  check_small(meshsal::load_mesh(dir.write("le.ply", binary_ply(false))));
}

TEST_CASE("OFF forms: comments, counts on the header line, colours, COFF", "[io]") {
  TempDir dir;
  const std::string off =
      "# leading comment\n"
      "OFF 5 2 0\n"
      "0 0 0\n1 0 0\n\n1 1 0  # comment\n0 1 0\n2 0.5 0.25\n"
      "4 0 1 2 3 255 0 0\n"
      "3 1 4 2 0.1 0.2 0.3 1.0\n";
  check_small(meshsal::load_mesh(dir.write("forms.off", off)));
  const std::string coff =
      "COFF\n5 2 7\n"
      "0 0 0 1 2 3 4\n1 0 0 1 2 3 4\n1 1 0 1 2 3 4\n0 1 0 1 2 3 4\n2 0.5 0.25 1 2 3 4\n"
      "4 0 1 2 3\n3 1 4 2\n";
  check_small(meshsal::load_mesh(dir.write("colour.OFF", coff)));
  check_small(meshsal::load_mesh(dir.write_gz("colour.off.gz", coff)));
}

TEST_CASE("gzip files with several members load as one", "[io]") {
  TempDir dir;
  std::string a = "v 0 0 0\nv 1 0 0\nv 1 1 0\n", b = "v 0 1 0\nv 2 0.5 0.25\nf 1 2 3 4\nf 2 5 3\n";
  std::string pa = dir.write_gz("a.gz", a), pb = dir.write_gz("b.gz", b);
  std::string both = meshsal_test::read_file(pa) + meshsal_test::read_file(pb);
  check_small(meshsal::load_mesh(dir.write("joined.obj.gz", both)));
}

namespace {

// A 300 x 300 grid as binary PLY (float x y z and a float quality; faces with a uchar
// count and int indices): 90,000 vertices and 178,802 triangles, enough records for the
// vertex and triangle copies to run in many ranges on every core. Cell k's two triangles
// are (a b c) (a c d); with `quad` set, cell `quad` is written as the quad (a b c d) instead,
// which fans to the same two triangles. `bad` >= 0 puts an out-of-range index in that face.
struct GridPly {
  std::string bytes;
  std::vector<uint32_t> triangles;
  std::vector<float> quality;
};

GridPly grid_ply(long quad, long bad) {
  const uint32_t w = 300;
  GridPly g;
  std::string body;
  for (uint32_t i = 0; i < w; ++i)
    for (uint32_t j = 0; j < w; ++j) {
      put_bin<float>(body, float(j), false);
      put_bin<float>(body, float(i), false);
      put_bin<float>(body, float((i * 7 + j * 3) % 5) * 0.25f, false);
      const float q = float(i * w + j) * 0.5f;
      put_bin<float>(body, q, false);
      g.quality.push_back(q);
    }
  long faces = 0;
  for (uint32_t i = 0; i + 1 < w; ++i)
    for (uint32_t j = 0; j + 1 < w; ++j) {
      const uint32_t a = i * w + j, b = a + 1, c = a + w + 1, d = a + w;
      g.triangles.insert(g.triangles.end(), {a, b, c, a, c, d});
      const long cell = long(i) * (w - 1) + j;
      auto face = [&](std::initializer_list<uint32_t> corners) {
        put_bin<uint8_t>(body, uint8_t(corners.size()));
        for (uint32_t v : corners) put_bin<int32_t>(body, faces == bad ? int32_t(w * w + 5) : int32_t(v), false);
        ++faces;
      };
      if (cell == quad) {
        face({a, b, c, d});
      } else {
        face({a, b, c});
        face({a, c, d});
      }
    }
  g.bytes = "ply\nformat binary_little_endian 1.0\nelement vertex " + std::to_string(w * w) +
            "\nproperty float x\nproperty float y\nproperty float z\nproperty float quality\nelement face " +
            std::to_string(faces) + "\nproperty list uchar int vertex_indices\nend_header\n" + body;
  return g;
}

}  // namespace

TEST_CASE("PLY binary of many records: the copies on every core read what one record at a time reads", "[io]") {
  // All triangles: the parallel copy.
  const GridPly plain = grid_ply(-1, -1);
  meshsal::LoadOptions with;
  with.attributes = true;
  meshsal::LoadedMesh read = meshsal::read_mesh_bytes(plain.bytes, "grid.ply", with);
  CHECK(read.mesh.vertex_count() == 90000);
  CHECK(read.mesh.triangles == plain.triangles);
  CHECK(read.properties["quality"] == plain.quality);
  CHECK(read.mesh.positions[3 * 45123 + 0] - read.mesh.positions[0] == 123.0f);  // vertex (150, 123)
  // A quad far into the faces (cell 80000, after more than two 65,536-face ranges): the copy
  // gives up and the record-at-a-time loop reads the same triangles from the start.
  const GridPly quad = grid_ply(80000, -1);
  CHECK(quad.bytes.size() == plain.bytes.size() - 9);  // one 17-byte quad for two 13-byte triangles
  CHECK(meshsal::load_mesh_bytes(quad.bytes, "quad.ply").triangles == plain.triangles);
  // An index out of range there is named by the face, as the one-at-a-time loop names it.
  CHECK_THROWS_WITH(meshsal::load_mesh_bytes(grid_ply(-1, 150001).bytes, "bad.ply"),
                    Catch::Contains("face 150001") && Catch::Contains("out of range (90000 vertices)"));
  CHECK_THROWS_WITH(meshsal::load_mesh_bytes(grid_ply(80000, 170000).bytes, "bad.ply"),
                    Catch::Contains("face 170000") && Catch::Contains("out of range"));
}

TEST_CASE("PLY stream (out of core): faces from the read-ahead are the loader's, a bad face named", "[io][outofcore]") {
  TempDir dir;
  auto stream_all = [&](const std::string& name, const std::string& bytes) {
    meshsal::PlyStream s(dir.write(name, bytes));
    std::vector<double> xyz(3 * 4096);
    while (s.read_vertices(xyz.data(), 4096) > 0) {
    }
    std::vector<uint32_t> triangles;
    while (s.read_faces(triangles, 1000) > 0) {  // 1000 faces a call: calls end inside the read-ahead
    }
    return triangles;
  };
  const GridPly plain = grid_ply(-1, -1);
  CHECK(stream_all("plain.ply", plain.bytes) == plain.triangles);
  CHECK(stream_all("quad.ply", grid_ply(80000, -1).bytes) == plain.triangles);
  CHECK_THROWS_WITH(stream_all("bad.ply", grid_ply(-1, 150001).bytes),
                    Catch::Contains("face 150001 uses vertex 90005 but the file has 90000 vertices"));
  // Cut inside the last face: the header's counts are not all there.
  CHECK_THROWS_WITH(stream_all("cut.ply", plain.bytes.substr(0, plain.bytes.size() - 5)),
                    Catch::Contains("the file ends before its header's counts are read"));
}

TEST_CASE("PLY stream (out of core): ranges read apart are the whole read's, and where it cannot seek it says so", "[io][outofcore]") {
  // The ranks building a store each read their share of the vertices and faces (seek_vertex,
  // seek_face): pieces in any order join into the front-to-back read.
  TempDir dir;
  const GridPly plain = grid_ply(-1, -1);
  const std::string path = dir.write("plain.ply", plain.bytes);
  std::vector<double> whole(3 * 90000);
  {
    meshsal::PlyStream s(path);
    REQUIRE(s.ranged());
    REQUIRE(s.read_vertices(whole.data(), 90000) == 90000);
  }
  const uint64_t faces = plain.triangles.size() / 3;
  for (const uint64_t parts : {1, 3, 7}) {
    INFO(parts << " parts");
    std::vector<double> xyz(whole.size(), -1);
    std::vector<uint32_t> triangles(plain.triangles.size(), UINT32_MAX);
    for (uint64_t p = parts; p-- > 0;) {  // the last part first
      meshsal::PlyStream s(path);
      const uint64_t v0 = 90000 * p / parts, v1 = 90000 * (p + 1) / parts;
      s.seek_vertex(v0);
      CHECK(s.read_vertices(&xyz[3 * v0], size_t(v1 - v0)) == v1 - v0);
      const uint64_t f0 = faces * p / parts, f1 = faces * (p + 1) / parts;
      s.seek_face(f0);
      std::vector<uint32_t> t;
      while (t.size() < 3 * (f1 - f0) && s.read_faces(t, size_t(f1 - f0 - t.size() / 3)) > 0) {
      }
      REQUIRE(t.size() == 3 * (f1 - f0));
      std::copy(t.begin(), t.end(), triangles.begin() + long(3 * f0));
    }
    CHECK(xyz == whole);
    CHECK(triangles == plain.triangles);
  }
  // Not in ranges: a quad among the faces (the size is not triangles'), a gzipped file, a
  // list in the vertex element, an element of lists before the faces; the file cut short.
  CHECK_FALSE(meshsal::PlyStream(dir.write("quad.ply", grid_ply(80000, -1).bytes)).ranged());
  const std::string gz = (dir.path / "plain.ply.gz").string();
  {
    gzFile out = gzopen(gz.c_str(), "wb");
    REQUIRE(gzwrite(out, plain.bytes.data(), unsigned(plain.bytes.size())) == int(plain.bytes.size()));
    gzclose(out);
  }
  CHECK_FALSE(meshsal::PlyStream(gz).ranged());
  const std::string one_triangle = "element face 1\nproperty list uchar int vertex_indices\nend_header\n";
  std::string tri_body;
  put_bin<uint8_t>(tri_body, 3);
  for (int32_t v : {0, 1, 2}) put_bin<int32_t>(tri_body, v, false);
  auto vertices = [](int lists) {
    std::string b;
    for (int i = 0; i < 3; ++i) {
      for (int a = 0; a < 3; ++a) put_bin<float>(b, float(i == a), false);
      if (lists) put_bin<uint8_t>(b, 0);
    }
    return b;
  };
  const std::string head = "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n";
  CHECK(meshsal::PlyStream(dir.write("ok.ply", head + one_triangle + vertices(0) + tri_body)).ranged());
  // The coordinates kept as floats (the out-of-core store's xyz) only where every value fits.
  CHECK(meshsal::PlyStream(path).positions_fit_float());
  for (const char* type : {"double", "int", "uint"}) {
    std::string h = "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty " +
                    std::string(type) + " y\nproperty float z\n";
    CHECK_FALSE(meshsal::PlyStream(dir.write(std::string(type) + ".ply", h + one_triangle)).positions_fit_float());
  }
  CHECK(meshsal::PlyStream(dir.write("short.ply", "ply\nformat binary_little_endian 1.0\nelement vertex 3\n"
                                                  "property short x\nproperty ushort y\nproperty uchar z\n" +
                                                  one_triangle))
            .positions_fit_float());
  CHECK_FALSE(meshsal::PlyStream(dir.write("vlist.ply", head + "property list uchar int extra\n" + one_triangle +
                                                        vertices(1) + tri_body))
                  .ranged());
  CHECK_FALSE(meshsal::PlyStream(dir.write("edges.ply", head + "element edge 0\nproperty list uchar int v\n" +
                                                        one_triangle + vertices(0) + tri_body))
                  .ranged());
  CHECK_FALSE(meshsal::PlyStream(dir.write("cut.ply", head + one_triangle + vertices(0) + tri_body.substr(0, 9))).ranged());
}
