// What a loader tells while it reads (io/read_observer.h): a PLY's positions before its
// faces, as the mesh keeps them, then its triangles, and the observer ended before the
// loader returns, throws or changes what it gave.
#include <catch2/catch.hpp>

#include <cstring>
#include <string>
#include <vector>

#include "cli/synthetic.h"
#include "io/read_observer.h"
#include "meshsal/meshsal.h"
#include "test_io_util.h"

using namespace meshsal;
using meshsal_test::TempDir;

namespace {

// Copies what it is given, and the order of the calls.
struct Recorder final : ReadObserver {
  std::vector<std::string> calls;
  std::vector<float> positions;
  std::vector<uint32_t> triangles;
  void positions_read(const float* p, size_t n) override {
    calls.push_back("positions");
    positions.assign(p, p + 3 * n);
  }
  void triangles_read(const uint32_t* t, size_t n) override {
    calls.push_back("triangles");
    triangles.assign(t, t + 3 * n);
  }
  void read_ended(bool returned) noexcept override { calls.push_back(returned ? "returned" : "ended"); }
};

bool same_bits(const std::vector<float>& a, const std::vector<float>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * 4) == 0;
}

// The mesh as read with the observer is the mesh read without one, bit for bit.
void check_same_mesh(const Mesh& with, const Mesh& without) {
  CHECK(same_bits(with.positions, without.positions));
  CHECK(with.triangles == without.triangles);
  CHECK(std::memcmp(with.origin, without.origin, sizeof with.origin) == 0);
  CHECK(with.source_positions == without.source_positions);
}

// A small ASCII PLY: a quad of two triangles (z = 1.5 and 2.5).
const char* kAsciiPly =
    "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
    "element face 2\nproperty list uchar int vertex_indices\nend_header\n"
    "0 0 1.5\n1 0 1.5\n1 1 2.5\n0 1 2.5\n3 0 1 2\n3 0 2 3\n";

}  // namespace

TEST_CASE("read observer: a PLY's positions before its faces, as the mesh keeps them", "[io]") {
  const TempDir dir;
  const Mesh sphere = make_bumpy_sphere(3);
  write_mesh(dir.file("sphere.ply"), sphere);  // binary
  for (const std::string& path : {dir.file("sphere.ply"), dir.write("quad.ply", kAsciiPly)}) {
    INFO(path);
    Recorder seen;
    const LoadedMesh read = read_mesh_observed(path, {}, &seen);
    CHECK(seen.calls == std::vector<std::string>{"positions", "triangles", "returned"});
    CHECK(same_bits(seen.positions, read.mesh.positions));
    CHECK(seen.triangles == read.mesh.triangles);
    check_same_mesh(read.mesh, load_mesh(path));
  }
}

TEST_CASE("read observer: positions made early at another origin are ended first, then made again", "[io]") {
  // A vertex no triangle uses, far out: the box of all the vertices (the early origin) is
  // not the mesh points' box (the mesh's origin), so the positions told are not the mesh's.
  const TempDir dir;
  Mesh mesh = make_bumpy_sphere(2);
  mesh.positions.insert(mesh.positions.end(), {40.0f, 3.0f, -7.0f});
  write_mesh(dir.file("loose.ply"), mesh);
  Recorder seen;
  const LoadedMesh read = read_mesh_observed(dir.file("loose.ply"), {}, &seen);
  // Ended before the positions change, told nothing more; then told the load returned.
  CHECK(seen.calls == std::vector<std::string>{"positions", "ended", "returned"});
  CHECK_FALSE(same_bits(seen.positions, read.mesh.positions));
  CHECK(read.mesh.origin[0] != 0.0);
  check_same_mesh(read.mesh, load_mesh(dir.file("loose.ply")));
}

TEST_CASE("read observer: a PLY with seams is computed on other arrays, so its observer is ended", "[io]") {
  // Two triangles on one square whose shared edge is split: vertices 3 and 4 sit where 1
  // and 2 do, with another u (a UV seam).
  const TempDir dir;
  const std::string path = dir.write("seam.ply",
                                     "ply\nformat ascii 1.0\nelement vertex 6\nproperty float x\nproperty float y\n"
                                     "property float z\nproperty float u\nelement face 2\n"
                                     "property list uchar int vertex_indices\nend_header\n"
                                     "0 0 0 0\n1 0 0 0\n0 1 0 0\n1 0 0 1\n0 1 0 1\n1 1 0 1\n3 0 1 2\n3 3 5 4\n");
  Recorder seen;
  const LoadedMesh read = read_mesh_observed(path, {}, &seen);
  REQUIRE_FALSE(read.mesh.position_vertex.empty());
  CHECK(seen.calls == std::vector<std::string>{"positions", "triangles", "ended", "returned"});
  check_same_mesh(read.mesh, load_mesh(path));
}

TEST_CASE("read observer: a load that fails after telling ends the observer", "[io]") {
  const TempDir dir;
  std::string bad = kAsciiPly;
  bad.replace(bad.find("3 0 2 3"), 7, "3 0 2 9");  // a face past the 4 vertices
  Recorder seen;
  CHECK_THROWS_WITH(read_mesh_observed(dir.write("bad.ply", bad), {}, &seen),
                    Catch::Contains("out of range"));
  REQUIRE_FALSE(seen.calls.empty());
  CHECK(seen.calls.front() == "positions");
  CHECK(seen.calls.back() == "ended");
  // Formats that tell nothing yet only end it.
  Recorder obj;
  const std::string path = dir.write("quad.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nf 1 2 3\n");
  CHECK(read_mesh_observed(path, {}, &obj).mesh.triangle_count() == 1);
  CHECK(obj.calls == std::vector<std::string>{"returned"});
  // And none is fine.
  CHECK(read_mesh_observed(path, {}, nullptr).mesh.triangle_count() == 1);
}
