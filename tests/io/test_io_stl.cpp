// [io] STL input: ASCII and binary (told apart by the size 84 + 50 n, not by "solid"),
// corners welded into shared vertices in order of first appearance, and bad STL refused
// with one-line messages that name the file.
#include <cmath>
#include <cstring>
#include <limits>
#include <set>
#include <utility>

#include "cli/synthetic.h"
#include "meshsal/meshsal.h"
#include "test_util.h"
#include "test_io_util.h"

using meshsal::Mesh;
using meshsal_test::put_bin;
using meshsal_test::TempDir;
using meshsal_test::expect_error;

namespace {

// Binary STL of `mesh`, every triangle's corners by value; `header` starts the 80 bytes.
std::string binary_stl(const Mesh& mesh, const std::string& header = "meshsal test") {
  std::string s = header;
  s.resize(80, ' ');
  put_bin<uint32_t>(s, static_cast<uint32_t>(mesh.triangle_count()));
  for (size_t t = 0; t < mesh.triangle_count(); ++t) {
    for (int k = 0; k < 3; ++k) put_bin(s, 0.0f);  // the normal, ignored by readers
    for (int c = 0; c < 3; ++c)
      for (int k = 0; k < 3; ++k) put_bin(s, mesh.positions[3 * mesh.triangles[3 * t + c] + k]);
    put_bin<uint16_t>(s, 0);
  }
  return s;
}

size_t edge_count(const Mesh& m) {
  std::set<std::pair<uint32_t, uint32_t>> edges;
  for (size_t t = 0; t < m.triangle_count(); ++t)
    for (int k = 0; k < 3; ++k) {
      uint32_t a = m.triangles[3 * t + k], b = m.triangles[3 * t + (k + 1) % 3];
      edges.insert({std::min(a, b), std::max(a, b)});
    }
  return edges.size();
}

// Two triangles sharing the edge (1,0,0)-(0,1,0), in ASCII.
const std::string kTwoFacets =
    "solid square\n"
    "  facet normal 0 0 1\n    outer loop\n      vertex 0 0 0\n      vertex 1 0 0\n"
    "      vertex 0 1 0\n    endloop\n  endfacet\n"
    "  facet normal 0 0 1\n    outer loop\n      vertex 1 0 0\n      vertex 1 1 0\n"
    "      vertex 0 1 0\n    endloop\n  endfacet\n"
    "endsolid square\n";


}  // namespace

TEST_CASE("STL binary: a closed sphere welds to a closed mesh (V - E + F = 2)", "[io][stl]") {
  TempDir dir;
  const Mesh sphere = meshsal::make_sphere(1.0, 2);  // 162 vertices, 320 triangles
  const std::string path = dir.write("sphere.stl", binary_stl(sphere));
  const meshsal::LoadedMesh read = meshsal::read_mesh(path);
  const Mesh& m = read.mesh;
  const meshsal::LoadReport& report = read.report;
  REQUIRE(m.triangle_count() == 320);
  CHECK(m.vertex_count() == 162);
  CHECK(report.welded_corners == 3 * 320 - 162);
  CHECK(int64_t(m.vertex_count()) - int64_t(edge_count(m)) + int64_t(m.triangle_count()) == 2);
  // Every corner keeps its position, and vertices come in order of first appearance.
  uint32_t next = 0;
  for (size_t c = 0; c < m.triangles.size(); ++c) {
    const uint32_t v = m.triangles[c];
    REQUIRE(v <= next);
    if (v == next) ++next;
    for (int k = 0; k < 3; ++k)
      CHECK(m.positions[3 * v + k] == sphere.positions[3 * sphere.triangles[c] + k]);
  }
}

TEST_CASE("STL binary whose header starts with 'solid' is read as binary", "[io][stl]") {
  TempDir dir;
  const Mesh sphere = meshsal::make_sphere(1.0, 1);
  const Mesh m = meshsal::load_mesh(dir.write("solid.stl", binary_stl(sphere, "solid exported by CAD")));
  CHECK(m.triangle_count() == 80);
  CHECK(m.vertex_count() == 42);
  // Gzipped, upper-case extension.
  CHECK(meshsal::load_mesh(dir.write_gz("SOLID.STL.GZ", binary_stl(sphere, "solid x"))).vertex_count() == 42);
}

TEST_CASE("STL ASCII: welded, first-appearance order, gz, CRLF, BOM, several solids", "[io][stl]") {
  TempDir dir;
  meshsal::LoadedMesh read = meshsal::read_mesh(dir.write("square.stl", kTwoFacets));
  Mesh m = std::move(read.mesh);
  CHECK(meshsal_test::world_floats(m) == std::vector<float>{0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0});
  CHECK(m.triangles == std::vector<uint32_t>{0, 1, 2, 1, 3, 2});
  CHECK(read.report.welded_corners == 2);

  std::string crlf;
  for (char c : kTwoFacets) crlf += c == '\n' ? std::string("\r\n") : std::string(1, c);
  CHECK(meshsal::load_mesh(dir.write("crlf.stl", "\xEF\xBB\xBF" + crlf)).triangles == m.triangles);
  CHECK(meshsal::load_mesh(dir.write_gz("square.stl.gz", kTwoFacets)).positions == m.positions);

  // Two solids (some exporters write one per part) make one mesh; -0 welds with +0.
  const std::string second =
      "solid part2\nfacet normal 0 0 1 outer loop vertex -0 0 0 vertex 0 1 0 vertex -1 0 0\n"
      "endloop endfacet\nendsolid\n";
  read = meshsal::read_mesh(dir.write("two.stl", kTwoFacets + second));
  m = std::move(read.mesh);
  CHECK(m.vertex_count() == 5);
  CHECK(m.triangles == std::vector<uint32_t>{0, 1, 2, 1, 3, 2, 0, 2, 4});
  CHECK(read.report.welded_corners == 4);

  // Other formats report nothing welded.
  CHECK(meshsal::read_mesh(dir.write("tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")).report.welded_corners == 0);
}

TEST_CASE("STL bad input: truncated, counts against size, NaN, garbled", "[io][stl]") {
  TempDir dir;
  const std::string good = binary_stl(meshsal::make_sphere(1.0, 0));  // 20 triangles, 1084 bytes
  REQUIRE(good.size() == 84 + 50 * 20);
  expect_error(dir.write("cut.stl", good.substr(0, good.size() - 7)),
               "binary STL: the header says 20 triangles (1084 bytes) but the file has 1077 bytes (truncated?)");
  expect_error(dir.write("long.stl", good + std::string(50, '\0')),
               "the header says 20 triangles (1084 bytes) but the file has 1134 bytes");
  std::string count = good;
  count[80] = 21;
  expect_error(dir.write("count.stl", count), "the header says 21 triangles");
  // A binary file of the wrong size whose header starts with "solid" is still binary.
  expect_error(dir.write("solidcut.stl", binary_stl(meshsal::make_sphere(1.0, 0), "solid x").substr(0, 1000)),
               "binary STL: the header says 20 triangles");
  expect_error(dir.write("short.stl", "abc"), "not an STL file (3 bytes");
  expect_error(dir.write("empty.stl", ""), "not an STL file (0 bytes");

  std::string nan = good;
  const float q = std::numeric_limits<float>::quiet_NaN();
  std::memcpy(&nan[84 + 50 * 3 + 12 + 4], &q, 4);
  expect_error(dir.write("nan.stl", nan), "facet 3 has a non-finite coordinate");
  std::string inf = kTwoFacets;
  inf.replace(inf.find("vertex 1 1 0"), 12, "vertex 1 inf 0");
  expect_error(dir.write("inf.stl", inf), "facet 1 has a non-finite coordinate");

  expect_error(dir.write("noend.stl", kTwoFacets.substr(0, kTwoFacets.find("endsolid"))),
               "truncated: the file ends without 'endsolid'");
  expect_error(dir.write("midfacet.stl", kTwoFacets.substr(0, kTwoFacets.find("vertex 1 1 0") + 9)),
               "truncated: the file ends inside a facet");
  std::string garbled = kTwoFacets;
  garbled.replace(garbled.find("outer loop"), 10, "outer lop");
  expect_error(dir.write("garbled.stl", garbled), "line 3: expected 'loop', found 'lop'");
  std::string coord = kTwoFacets;
  coord.replace(coord.find("vertex 1 0 0"), 12, "vertex 1,5 0 0");
  expect_error(dir.write("coord.stl", coord), "line 5: bad coordinate '1,5'");
  expect_error(dir.write("nofacet.stl", "solid empty\nendsolid empty\n"), "STL file has no facets");
  expect_error(dir.write("junk.stl", kTwoFacets + "junk\n"), "expected 'solid', found 'junk'");
  expect_error(dir.write_gz("bomb.stl.gz", good.substr(0, 80) + std::string("\x01\x00\x00\x00", 4) +
                                               std::string(4000, 'x')),
               "the header says 1 triangles (134 bytes) but the file has 4084 bytes");
}
