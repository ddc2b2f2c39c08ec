// [io] writers: bit-exact round trips through write_ply / write_obj and load_mesh, the
// SPEC section 4 header, and the all-or-nothing file replacement.
#include <unistd.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <vector>

#include "meshsal/meshsal.h"
#include "test_util.h"
#include "test_io_util.h"

using meshsal::Mesh;
using meshsal::VertexProperties;
using meshsal_test::TempDir;

namespace {

// A tetrahedron with awkward float values (non-round decimals, tiny, huge, subnormal).
Mesh awkward_mesh() {
  Mesh m;
  m.positions = {0.1f, -0.2f, 1e-7f, 3.4e38f, 1.0f / 3.0f, -0.0f, 1e-40f, 123456.789f, 2.5f,
                 -7.25e-3f, 0.3f, 6.02e23f, 0.0f, 0.0f, 0.0f};
  m.triangles = {0, 1, 2, 0, 2, 3, 1, 4, 2, 4, 3, 2};
  return m;
}

bool same_bits(const std::vector<float>& a, const std::vector<float>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0;
}

}  // namespace

TEST_CASE("write_ply round trip: positions bit-exact, triangles, properties, colours", "[io]") {
  TempDir dir;
  Mesh m = awkward_mesh();
  std::vector<double> quality = {0.0, 0.25, 1.0 / 3.0, 1e-30, -2.0};
  std::vector<double> curvature = {5, 4, 3, 2, 1};
  std::vector<uint8_t> rgb = {0, 1, 2, 255, 254, 253, 10, 20, 30, 40, 50, 60, 70, 80, 90};
  const std::string path = dir.file("out.ply");
  meshsal::write_ply(path, m, {{"quality", &quality}, {"curvature", &curvature}}, rgb);

  meshsal::LoadedMesh read = meshsal::read_mesh(path);
  const Mesh& back = read.mesh;
  VertexProperties& props = read.properties;
  CHECK(same_bits(meshsal_test::world_floats(back), m.positions));
  CHECK(back.triangles == m.triangles);
  REQUIRE(props.size() == 5);
  for (size_t v = 0; v < 5; ++v) {
    CHECK(props["quality"][v] == static_cast<float>(quality[v]));
    CHECK(props["curvature"][v] == static_cast<float>(curvature[v]));
    CHECK(props["red"][v] == rgb[3 * v]);
    CHECK(props["green"][v] == rgb[3 * v + 1]);
    CHECK(props["blue"][v] == rgb[3 * v + 2]);
  }
  CHECK(dir.entries() == 1);  // no temporary left behind
}

TEST_CASE("write_ply header follows SPEC section 4", "[io]") {
  TempDir dir;
  Mesh m = awkward_mesh();
  std::vector<double> q(5, 1.0);
  std::vector<uint8_t> rgb(15, 7);
  const std::string path = dir.file("spec.ply");
  meshsal::write_ply(path, m, {{"quality", &q}}, rgb);
  const std::string bytes = meshsal_test::read_file(path);
  const std::string header =
      "ply\nformat binary_little_endian 1.0\ncomment written by meshsal\n"
      "element vertex 5\nproperty float x\nproperty float y\nproperty float z\n"
      "property float quality\nproperty uchar red\nproperty uchar green\nproperty uchar blue\n"
      "element face 4\nproperty list uchar int vertex_indices\nend_header\n";
  REQUIRE(bytes.compare(0, header.size(), header) == 0);
  // Body: 5 * (3*4 + 4 + 3) vertex bytes + 4 * (1 + 3*4) face bytes, nothing more.
  CHECK(bytes.size() == header.size() + 5 * 19 + 4 * 13);
  float x0;
  std::memcpy(&x0, bytes.data() + header.size(), 4);
  CHECK(x0 == 0.1f);
  CHECK(static_cast<unsigned char>(bytes[header.size() + 5 * 19]) == 3);
}

TEST_CASE("write_ply without properties or colours", "[io]") {
  TempDir dir;
  Mesh m = awkward_mesh();
  const std::string path = dir.file("plain.ply");
  meshsal::write_ply(path, m, {});
  const meshsal::LoadedMesh read = meshsal::read_mesh(path);
  const Mesh& back = read.mesh;
  const VertexProperties& props = read.properties;
  CHECK(same_bits(meshsal_test::world_floats(back), m.positions));
  CHECK(back.triangles == m.triangles);
  CHECK(props.empty());
}

TEST_CASE("write_obj round trip is bit-exact", "[io]") {
  TempDir dir;
  Mesh m = awkward_mesh();
  const std::string path = dir.file("out.obj");
  meshsal::write_obj(path, m);
  Mesh back = meshsal::load_mesh(path);
  CHECK(same_bits(meshsal_test::world_floats(back), m.positions));
  CHECK(back.triangles == m.triangles);
  CHECK(dir.entries() == 1);
}

TEST_CASE("writers throw and leave nothing when the folder does not exist", "[io]") {
  TempDir dir;
  Mesh m = awkward_mesh();
  const std::string path = dir.file("missing/sub/out.ply");
  CHECK_THROWS_WITH(meshsal::write_ply(path, m, {}), Catch::Contains("does not exist") && Catch::Contains(path));
  CHECK_THROWS_AS(meshsal::write_obj(dir.file("missing/out.obj"), m), meshsal::Error);
  CHECK(dir.entries() == 0);
}

TEST_CASE("an existing file is replaced only when the write succeeds", "[io]") {
  TempDir dir;
  Mesh m = awkward_mesh();
  const std::string path = dir.write("keep.ply", "old contents");
  std::vector<double> wrong_size(3, 1.0);  // 3 values for 5 vertices: must fail
  CHECK_THROWS_WITH(meshsal::write_ply(path, m, {{"quality", &wrong_size}}),
                    Catch::Contains("quality") && Catch::Contains(path));
  std::vector<uint8_t> short_rgb(14, 0);
  CHECK_THROWS_AS(meshsal::write_ply(path, m, {}, short_rgb), meshsal::Error);
  Mesh bad = m;
  bad.triangles[4] = 99;
  CHECK_THROWS_AS(meshsal::write_ply(path, bad, {}), meshsal::Error);
  CHECK_THROWS_AS(meshsal::write_obj(path, bad), meshsal::Error);
  CHECK(meshsal_test::read_file(path) == "old contents");
  CHECK(dir.entries() == 1);

  meshsal::write_ply(path, m, {});
  CHECK(meshsal::load_mesh(path).triangle_count() == 4);
  CHECK(dir.entries() == 1);
}

TEST_CASE("writing into a read-only folder throws and leaves nothing", "[io]") {
  if (::geteuid() == 0) {
    meshsal_test::skip_case("running as root, folder permissions are not enforced");
    return;
  }
  TempDir dir;
  std::filesystem::permissions(dir.path, std::filesystem::perms::owner_read | std::filesystem::perms::owner_exec);
  Mesh m = awkward_mesh();
  CHECK_THROWS_WITH(meshsal::write_ply(dir.file("x.ply"), m, {}), Catch::Contains("x.ply"));
  CHECK_THROWS_AS(meshsal::write_obj(dir.file("x.obj"), m), meshsal::Error);
  std::filesystem::permissions(dir.path, std::filesystem::perms::owner_all);
  CHECK(dir.entries() == 0);
}

TEST_CASE("write_saliency_ply: quality = S, the extra properties, and colours over the mesh points", "[io]") {
  TempDir dir;
  Mesh m = awkward_mesh();
  m.positions = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 5, 5, 5};  // vertex 4: no triangle uses it
  m.triangles = {0, 1, 2, 0, 2, 3, 0, 3, 1, 1, 3, 2};
  const std::vector<double> s{0.5, 1.0, 0.25, 2.0, 100.0}, h{1, 2, 3, 4, 5};
  const std::string p = dir.file("s.ply");
  meshsal::write_saliency_ply(p, m, s, {{"curvature", &h}});
  VertexProperties props = meshsal::read_mesh(p).properties;
  CHECK(props.count("quality") == 1);
  CHECK(props.count("curvature") == 1);
  CHECK(props.count("red") == 1);
  CHECK(props["quality"] == std::vector<float>{0.5f, 1.0f, 0.25f, 2.0f, 100.0f});
  // The colour scale runs over the mesh points only: vertex 3 (the largest of them) gets the
  // top colour although vertex 4 holds 100; the same bytes as the explicit mask.
  CHECK(props["red"][3] > props["blue"][3]);  // the top: dark red
  CHECK(props["blue"][4] > props["red"][4]);  // outside the mesh points: the low end's blue
  const std::string q = dir.file("q.ply");
  const std::vector<uint8_t> mask{1, 1, 1, 1, 0};
  meshsal::write_saliency_ply(q, m, s, {{"curvature", &h}}, mask);
  CHECK(meshsal_test::read_file(p) == meshsal_test::read_file(q));
  CHECK_THROWS_WITH(meshsal::write_saliency_ply(p, m, std::vector<double>(3, 1.0)),
                    Catch::Contains("3 saliency values for 5 vertices"));
}
