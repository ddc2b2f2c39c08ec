// [io] bad input: every broken file gives one meshsal::Error whose one-line message names
// the file and the problem, without crashing or allocating absurd amounts.
#include <atomic>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <new>

#include "meshsal/meshsal.h"
#include "test_io_util.h"

using meshsal::Mesh;
using meshsal_test::put_bin;
using meshsal_test::TempDir;
using meshsal_test::expect_error;
using meshsal_test::expect_errors;

namespace {

const std::string kObjOk = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";

std::string ascii_ply(const std::string& vertices, const std::string& faces, int nv, int nf) {
  return "ply\nformat ascii 1.0\nelement vertex " + std::to_string(nv) +
         "\nproperty float x\nproperty float y\nproperty float z\nelement face " +
         std::to_string(nf) + "\nproperty list uchar int vertex_indices\nend_header\n" + vertices + faces;
}
const std::string kPlyV = "0 0 0\n1 0 0\n0 1 0\n";

// Binary LE PLY of one triangle; `tri` are its indices, `nv` / `nf` the header counts.
std::string binary_ply(std::vector<int32_t> tri = {0, 1, 2}, uint64_t nv = 3, uint64_t nf = 1,
                       float x0 = 0.0f) {
  std::string s = "ply\nformat binary_little_endian 1.0\nelement vertex " + std::to_string(nv) +
                  "\nproperty float x\nproperty float y\nproperty float z\nelement face " +
                  std::to_string(nf) + "\nproperty list uchar int vertex_indices\nend_header\n";
  const float p[9] = {x0, 0, 0, 1, 0, 0, 0, 1, 0};
  for (float f : p) put_bin(s, f);
  put_bin<uint8_t>(s, static_cast<uint8_t>(tri.size()));
  for (int32_t i : tri) put_bin(s, i);
  return s;
}

}  // namespace

TEST_CASE("bad input: missing file, folder, unknown extension", "[io]") {
  TempDir dir;
  expect_error(dir.file("nope.obj"), "No such file");
  expect_error(dir.file("nope.ply.gz"), "No such file");
  std::filesystem::create_directory(dir.file("folder.ply"));
  expect_error(dir.file("folder.ply"), "folder");
  expect_error(dir.write("mesh.xyz", kObjOk), "unknown mesh format '.xyz' (expected .obj, .ply, .off, .stl, .gltf or .glb");
  expect_error(dir.write("mesh", kObjOk), "unknown mesh format");
  expect_error(dir.write("mesh.gz", kObjOk), "unknown mesh format");
  CHECK(meshsal_test::load_error(dir.write("fine.obj", kObjOk)).empty());
}

TEST_CASE("bad input: corrupt and truncated gzip", "[io]") {
  TempDir dir;
  expect_error(dir.write("plain.obj.gz", kObjOk), "not a gzip file");
  std::string gz = meshsal_test::read_file(dir.write_gz("good.ply.gz", binary_ply()));
  REQUIRE(meshsal_test::load_error(dir.file("good.ply.gz")).empty());
  expect_error(dir.write("cut.ply.gz", gz.substr(0, gz.size() / 2)), "truncated gzip");
  std::string garbled = gz;
  for (size_t i = 12; i < garbled.size() - 8; ++i) garbled[i] = static_cast<char>(0xA5 ^ i);
  expect_error(dir.write("garbled.ply.gz", garbled), "corrupt gzip");
  expect_error(dir.write("tail.ply.gz", gz + "junk"), "after the gzip stream");
}

TEST_CASE("bad input: truncated files", "[io]") {
  TempDir dir;
  const std::string bin = binary_ply();
  // Cut inside the face list (header check passes: the minimum sizes still fit).
  expect_error(dir.write("cut_face.ply", bin.substr(0, bin.size() - 2)), "truncated");
  // Cut inside the vertices: caught by the size check before reading.
  expect_error(dir.write("cut_vert.ply", bin.substr(0, bin.size() - 30)), "truncated");
  // Cut inside the header.
  expect_error(dir.write("cut_head.ply", bin.substr(0, 40)), "end_header");
  expect_error(dir.write("cut.ply", ascii_ply(kPlyV, "3 0 1 2\n3 0 ", 3, 2)), "fewer");
  expect_error(dir.write("cut2.ply", ascii_ply(kPlyV, "", 3, 1)), "truncated");
  expect_error(dir.write("cut.off", "OFF\n3 2 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"), "truncated");
  expect_error(dir.write("cut2.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1\n"), "fewer");
  expect_error(dir.write("cut.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2"), "needs at least 3");
}

TEST_CASE("bad input: garbled headers", "[io]") {
  TempDir dir;
  expect_error(dir.write("a.ply", "plx\nformat ascii 1.0\nend_header\n"), "not a PLY file");
  expect_error(dir.write("b.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty flaot x\nend_header\n"),
               "unknown property type 'flaot'");
  expect_error(dir.write("c.ply", "ply\nformat binary_middle_endian 1.0\nend_header\n"), "unknown format");
  expect_error(dir.write("d.ply", "ply\nformat ascii 1.0\nproperty float x\nend_header\n"), "property before any element");
  expect_error(dir.write("e.ply", "ply\nformat ascii 1.0\nelement vertex three\nend_header\n"), "bad element line");
  expect_error(dir.write("f.ply", "ply\nformat ascii 1.0\nelephant vertex 3\nend_header\n"), "unexpected header line");
  expect_error(dir.write("g.ply", "ply\nelement vertex 0\nend_header\n"), "format");
  expect_error(dir.write("h.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n"
                                  "property float y\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
                                  "0 0\n1 0\n0 1\n3 0 1 2\n"),
               "lacks an x, y or z");
  expect_error(dir.write("i.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                                  "property float z\nelement face 1\nproperty list uchar int other\nend_header\n" +
                                      kPlyV + "3 0 1 2\n"),
               "no vertex_indices");
  expect_error(dir.write("j.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                                  "property float z\nend_header\n" + kPlyV),
               "no 'face' element");
  expect_error(dir.write("k.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                                  "property float z\nelement tristrips 1\nproperty list int int vertex_indices\n"
                                  "end_header\n" + kPlyV + "3 0 1 2\n"),
               "tristrips");
  expect_error(dir.write("a.off", "NOT\n3 1 0\n"), "not an OFF file");
  expect_error(dir.write("b.off", "OFF\n3 x 0\n"), "bad count");
  expect_error(dir.write("c.off", "OFF BINARY\n3 1 0\n"), "binary OFF");
  expect_error(dir.write("d.off", ""), "empty file");
  // Binary garbage under an .obj name has no vertices.
  expect_error(dir.write("bin.obj", std::string("\x01\x02\x00\xff garbage", 12)), "no vertices");
}

TEST_CASE("bad input: header counts that disagree with the body", "[io]") {
  TempDir dir;
  // Fewer elements in the header than in the body.
  expect_error(dir.write("more.ply", ascii_ply(kPlyV + "0 0 1\n", "3 0 1 2\n", 3, 1)), "line 13: face 0 has 0 vertices");
  expect_error(dir.write("more2.ply", ascii_ply(kPlyV, "3 0 1 2\n3 0 2 1\n", 3, 1)), "after the last element");
  expect_error(dir.write("more.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n3 0 2 1\n"), "more data");
  std::string bin = binary_ply();
  expect_error(dir.write("more_bin.ply", bin + std::string("\x03\x00\x00\x00\x00", 5)), "after the last element");
  // More elements in the header than in the body.
  expect_error(dir.write("fewer.ply", ascii_ply(kPlyV, "3 0 1 2\n", 4, 1)), "line 13: vertex 3 has more values");
  expect_error(dir.write("fewer2.ply", ascii_ply(kPlyV, "3 0 1 2\n", 3, 2)), "truncated");
  expect_error(dir.write("fewer_bin.ply", binary_ply({0, 1, 2}, 3, 2)), "truncated");
  expect_error(dir.write("fewer.off", "OFF\n4 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"), "header says 1 faces");
  expect_error(dir.write("rows.ply", ascii_ply("0 0 0 0\n1 0 0\n0 1 0\n", "3 0 1 2\n", 3, 1)), "more values");
}

TEST_CASE("bad input: indices out of range", "[io]") {
  TempDir dir;
  expect_error(dir.write("big.ply", ascii_ply(kPlyV, "3 0 1 3\n", 3, 1)), "vertex index 3");
  expect_error(dir.write("neg.ply", ascii_ply(kPlyV, "3 0 -1 2\n", 3, 1)), "vertex index -1");
  expect_error(dir.write("big_bin.ply", binary_ply({0, 1, 7})), "vertex index 7");
  expect_error(dir.write("neg_bin.ply", binary_ply({0, -5, 1})), "vertex index -5");
  expect_error(dir.write("big.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n"),
               "line 4: face index 4 is beyond the file's 3 vertices (OBJ indices start at 1)");
  // A forward reference is legal; one that the file never defines is named as written.
  expect_error(dir.write("fwd.obj", "v 0 0 0\nf 1 2 5\nv 1 0 0\nv 0 1 0\n"), "line 2: face index 5 is beyond the file's 3");
  expect_error(dir.write("big_vt.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/1 2/1 9/1\n"), "line 5: face index 9 is beyond");
  expect_error(dir.write("neg.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -1 -2 -4\n"), "before the first vertex");
  expect_error(dir.write("zero.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n"), "index 0");
  expect_error(dir.write("huge.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 99999999999999999999\n"), "bad face index");
  expect_error(dir.write("big.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n"), "face index 3");
  expect_error(dir.write("neg.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 -1 2\n"), "face index -1");
}

TEST_CASE("bad input: NaN and Inf coordinates", "[io]") {
  TempDir dir;
  expect_error(dir.write("nan.obj", "v 0 nan 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"), "non-finite");
  expect_error(dir.write("inf.obj", "v 0 0 0\nv 1 0 -inf\nv 0 1 0\nf 1 2 3\n"), "line 2: vertex 2 has a non-finite");
  expect_error(dir.write("overflow.obj", "v 0 0 0\nv 1 0 1e999\nv 0 1 0\nf 1 2 3\n"), "non-finite");
  expect_error(dir.write("nan.ply", ascii_ply("0 0 0\n1 0 0\n0 NaN 0\n", "3 0 1 2\n", 3, 1)), "non-finite");
  expect_error(dir.write("nan_bin.ply", binary_ply({0, 1, 2}, 3, 1, std::numeric_limits<float>::quiet_NaN())),
               "vertex 0 has a non-finite");
  expect_error(dir.write("inf_bin.ply", binary_ply({0, 1, 2}, 3, 1, std::numeric_limits<float>::infinity())),
               "non-finite");
  expect_error(dir.write("inf.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 1e400\n3 0 1 2\n"), "non-finite");
  expect_error(dir.write("text.obj", "v 0 0 0\nv 1 zero 0\nv 0 1 0\nf 1 2 3\n"), "bad vertex coordinate 'zero'");
  expect_error(dir.write("comma.ply", ascii_ply("0 0 0\n1,5 0 0\n0 1 0\n", "3 0 1 2\n", 3, 1)), "bad number '1,5'");
}

TEST_CASE("bad input: empty and degenerate meshes", "[io]") {
  TempDir dir;
  expect_errors(dir, {
      {"empty.obj", "", "no vertices"},
      {"points.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n", "no faces"},
      {"empty.ply", ascii_ply("", "", 0, 0), "no vertices"},
      {"nofaces.ply", ascii_ply(kPlyV, "", 3, 0), "no faces"},
      {"empty.off", "OFF\n0 0 0\n", "no vertices"},
      {"repeat.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 1 2\nf 3 3 3\n", "zero area"},
      {"line.obj", "v 0 0 0\nv 1 1 1\nv 3 3 3\nf 1 2 3\n", "zero area"},
      {"same.ply", ascii_ply("1 2 3\n1 2 3\n1 2 3\n", "3 0 1 2\n", 3, 1), "zero area"},
  });
}

TEST_CASE("bad input: faces with fewer than 3 vertices are errors", "[io]") {
  TempDir dir;
  expect_errors(dir, {
      {"two.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 2\n", "line 5: face with 2 vertices"},
      {"none.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf\nf 1 2 3\n", "face with 0 vertices"},
      {"two.ply", ascii_ply(kPlyV, "3 0 1 2\n2 0 1\n", 3, 2), "face 1 has 2 vertices"},
      {"zero.ply", ascii_ply(kPlyV, "0\n3 0 1 2\n", 3, 2), "face 0 has 0 vertices"},
      {"two_bin.ply", binary_ply({0, 1}), "face 0 has 2 vertices"},
      {"two.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n2 0 1\n", "face with 2 vertices"},
  });
}

// The largest single operator new request since the last reset: this test binary's
// operator new (plain and, through it, array new) records it, so a loader that sizes a
// buffer from a header's count before checking it against the file shows here.
namespace {
std::atomic<size_t> g_largest_new{0};
}  // namespace

void* operator new(std::size_t n) {
  size_t seen = g_largest_new.load(std::memory_order_relaxed);
  while (n > seen && !g_largest_new.compare_exchange_weak(seen, n, std::memory_order_relaxed)) {
  }
  if (void* p = std::malloc(n ? n : 1)) return p;
  throw std::bad_alloc();
}
// Every other form that pairs with these deletes comes from malloc too: the sanitizer's
// runtime has its own of each, and a block of its nothrow new freed here was a mismatch.
void* operator new(std::size_t n, const std::nothrow_t&) noexcept {
  try {
    return operator new(n);
  } catch (...) {
    return nullptr;
  }
}
void* operator new[](std::size_t n) { return operator new(n); }
void* operator new[](std::size_t n, const std::nothrow_t& t) noexcept { return operator new(n, t); }
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete(void* p, const std::nothrow_t&) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, const std::nothrow_t&) noexcept { std::free(p); }

TEST_CASE("bad input: absurd header counts fail without allocating for them", "[io]") {
  TempDir dir;
  // Each file is under 200 bytes and announces up to 2^64 elements: the loaders compare the
  // announced size with the file before reserving anything, so no request comes near even
  // 1 MiB (announced: 4e9 vertices = 48 GB). Not timed: speed is not the point (the header
  // check is what makes it fast), and wall time on a loaded machine cannot fail reliably.
  auto expect_error = [](const std::string& path, const std::string& problem) {
    g_largest_new = 0;
    meshsal_test::expect_error(path, problem);
    INFO("file: " << path << ": largest allocation " << g_largest_new << " bytes");
    CHECK(g_largest_new < (size_t(1) << 20));
  };
  expect_error(dir.write("huge_bin.ply", binary_ply({0, 1, 2}, 4000000000ull, 1)), "bytes but the body has");
  expect_error(dir.write("huge_faces.ply", binary_ply({0, 1, 2}, 3, 4000000000ull)), "bytes but the body has");
  expect_error(dir.write("huge_max.ply", binary_ply({0, 1, 2}, 18446744073709551615ull, 18446744073709551615ull)),
               "bytes but the body has");
  expect_error(dir.write("huge.ply", ascii_ply(kPlyV, "3 0 1 2\n", 2000000000, 1)), "bytes but the body has");
  expect_error(dir.write("overflow.ply", "ply\nformat ascii 1.0\nelement vertex 99999999999999999999\nend_header\n"),
               "bad element line");
  expect_error(dir.write("huge.off", "OFF\n4000000000 1 0\n0 0 0\n"), "larger than the file can hold");
  // A list length far beyond the file (255 indices announced, 3 present).
  std::string bin = binary_ply();
  bin[bin.size() - 13] = static_cast<char>(255);
  expect_error(dir.write("long_list.ply", bin), "truncated");
  expect_error(dir.write("long_list2.ply", ascii_ply(kPlyV, "4000000000 0 1 2\n", 3, 1)), "longer than the line");
}

TEST_CASE("validate_mesh on meshes built in memory", "[io]") {
  Mesh ok;
  ok.positions = {0, 0, 0, 1, 0, 0, 0, 1, 0, 5, 5, 5};  // vertex 3 unreferenced: allowed
  ok.triangles = {0, 1, 2, 0, 0, 1};                     // one degenerate triangle: allowed
  CHECK_NOTHROW(meshsal::validate_mesh(ok));

  Mesh m = ok;
  m.triangles[2] = 4;
  CHECK_THROWS_WITH(meshsal::validate_mesh(m), Catch::Contains("vertex index 4") && Catch::Contains("only 4 vertices"));
  m = ok;
  m.positions[4] = std::numeric_limits<float>::quiet_NaN();
  CHECK_THROWS_WITH(meshsal::validate_mesh(m), Catch::Contains("vertex 1 has a non-finite"));
  m = ok;
  m.positions[11] = -std::numeric_limits<float>::infinity();
  CHECK_THROWS_WITH(meshsal::validate_mesh(m), Catch::Contains("vertex 3 has a non-finite"));
  m = ok;
  m.triangles = {0, 1, 1};
  CHECK_THROWS_WITH(meshsal::validate_mesh(m), Catch::Contains("zero area"));
  CHECK_THROWS_WITH(meshsal::validate_mesh(Mesh{}), Catch::Contains("no vertices"));
  m = ok;
  m.triangles.clear();
  CHECK_THROWS_WITH(meshsal::validate_mesh(m), Catch::Contains("no faces"));
  m = ok;
  m.triangles.push_back(1);
  CHECK_THROWS_WITH(meshsal::validate_mesh(m), Catch::Contains("multiple of 3"));

  // Large arrays are checked on every core: still the first offender is named.
  Mesh big = ok;
  big.positions.resize(3 * 400000, 0.5f);
  for (size_t t = 0; t < 300000; ++t) big.triangles.insert(big.triangles.end(), {0, 1, 2});
  CHECK_NOTHROW(meshsal::validate_mesh(big));
  m = big;
  m.positions[3 * 350000 + 1] = std::numeric_limits<float>::quiet_NaN();
  m.positions[3 * 100001 + 2] = std::numeric_limits<float>::infinity();
  CHECK_THROWS_WITH(meshsal::validate_mesh(m), Catch::Contains("vertex 100001 has a non-finite"));
  m = big;
  m.triangles[3 * 290000] = 400000;
  m.triangles[3 * 123456 + 2] = 400007;
  CHECK_THROWS_WITH(meshsal::validate_mesh(m), Catch::Contains("triangle 123456 uses vertex index 400007"));
}
