// The mesh points built on the device (gpu_mesh_points.h) against their host twins: the
// positions less the box minimum as local_points packs them, bit for bit, and the flags as
// referenced_vertices marks them; on meshes with loose vertices and a box far from 0,
// a real scan, and under forced staging.
#include <catch2/catch.hpp>

#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "cli/synthetic.h"
#include "core/mesh_points.h"
#include "gpu/gpu_fast.h"
#include "gpu/gpu_mesh_points.h"
#include "gpu/gpu_saliency.h"
#include "gpu/vk_buffer.h"
#include "gpu/vk_compute.h"
#include "gpu/vk_context.h"
#include "meshsal/meshsal.h"
#include "test_util.h"

using namespace meshsal;

namespace {

vk::Context& context() {
  static std::unique_ptr<vk::Context> ctx = std::make_unique<vk::Context>(-1, true);
  return *ctx;
}

// `corners`: the triangles' indices as uploaded (a mesh's own, or with some out of range).
void check_points(vk::Context& ctx, const Mesh& mesh, const std::vector<uint32_t>& corners, const std::string& what) {
  INFO(what);
  const uint64_t before = vk::validation_message_count();
  const size_t nv = mesh.vertex_count();
  const std::vector<uint8_t> is_point = referenced_mask(corners.data(), corners.size(), nv);
  const BoundingBox box = mesh_points_bbox(mesh, is_point);
  const std::vector<double> host = gpu::local_points(mesh, {}, box, 2);

  vk::Buffer pos32 = gpu::upload_float_positions(ctx, mesh, 2);
  vk::Buffer triangles(ctx, corners.size() * 4, "test triangles");
  triangles.upload(corners.data(), corners.size() * 4);
  vk::Buffer pos(ctx, nv * 32, "test positions"), flags(ctx, nv * 4, "test flags");
  const std::vector<double> stale(4 * nv, 7.0);  // every entry must be written
  const std::vector<uint32_t> set(nv, 5u);       // and every flag cleared or set
  pos.upload(stale.data(), stale.size() * 8);
  flags.upload(set.data(), set.size() * 4);
  const gpu::DeviceMeshPoints points(ctx, pos32, triangles, pos, flags, uint32_t(nv), corners.size() / 3);
  vk::submit(ctx, "test", [&](VkCommandBuffer cmd) { points.record(ctx, cmd, box); });

  std::vector<double> device(4 * nv);
  std::vector<uint32_t> device_flags(nv);
  pos.download(device.data(), device.size() * 8);
  flags.download(device_flags.data(), device_flags.size() * 4);
  size_t differ = 0, wrong_flags = 0, points_count = 0;
  for (size_t i = 0; i < device.size(); ++i) differ += std::memcmp(&device[i], &host[i], 8) != 0;
  for (size_t v = 0; v < nv; ++v) {
    wrong_flags += device_flags[v] != is_point[v];
    points_count += is_point[v];
  }
  CHECK(differ == 0);
  CHECK(wrong_flags == 0);
  CHECK(points_count > 0);
  CHECK(vk::validation_message_count() == before);
}

// A bumpy sphere moved off the origin, with two loose vertices (one of a float denormal)
// and a degenerate triangle, and a triangle whose corners are 2^47 apart, so that a
// position less the box minimum rounds in double.
Mesh odd_sphere() {
  Mesh m = make_bumpy_sphere(3);
  for (size_t i = 0; i < m.positions.size(); ++i) m.positions[i] = m.positions[i] * 0.37f + (i % 3 == 0 ? 1234.5f : -3.25f);
  const uint32_t loose = uint32_t(m.vertex_count());
  m.positions.insert(m.positions.end(), {0.1f, 1e-40f, 0.3f, 5.0f, 5.0f, 5.0f});
  m.triangles.insert(m.triangles.end(), {0, 0, 5});
  const uint32_t far = loose + 2;
  m.positions.insert(m.positions.end(), {1.5e-5f, -7.0f, 2.5e-5f, 3.1e9f, -7.0f, 2.9e9f, 2.0f, 3.3e9f, 1.0f});
  m.triangles.insert(m.triangles.end(), {far, far + 1, far + 2});
  return m;
}

}  // namespace

TEST_CASE("gpu mesh points: positions and flags as their host twins", "[gpu][fast]") {
  vk::Context& ctx = context();
  const Mesh sphere = odd_sphere();
  check_points(ctx, sphere, sphere.triangles, "sphere far from 0, loose vertices");
  // Corners past the vertices (a mesh not validated) mark nothing, as on the host.
  std::vector<uint32_t> past = sphere.triangles;
  past.insert(past.end(), {uint32_t(sphere.vertex_count()), 0xffffffffu, 1});
  check_points(ctx, sphere, past, "corners past the vertices");
  const Mesh cube = make_cube(9);
  check_points(ctx, cube, cube.triangles, "cube");
}

TEST_CASE("gpu mesh points: a real scan, and under forced staging in small chunks", "[gpu][fast]") {
  vk::Context ctx(-1, true);
  ctx.use_staging = true;
  ctx.staging_chunk_limit = 64 << 10;  // the positions' fills start past 0
  const Mesh sphere = odd_sphere();
  check_points(ctx, sphere, sphere.triangles, "sphere, staged");
  MESHSAL_REQUIRE_MESH(path, "bunny_36k.obj");
  const Mesh bunny = load_mesh(path);
  const uint64_t copies = ctx.staged_copies;
  check_points(ctx, bunny, bunny.triangles, "bunny_36k, staged");
  CHECK(ctx.staged_copies - copies > 20);  // 575 KB of positions, 834 KB of triangles
  check_points(context(), bunny, bunny.triangles, "bunny_36k");
}

TEST_CASE("gpu saliency: uploads in small staged chunks give the same bits", "[gpu][fast]") {
  // The exact path's doubles and the fast path's floats packed chunk by chunk into the
  // staging area (their fills past the first chunk), against one chunk each.
  vk::Context whole(-1, true), chunked(-1, true);
  whole.use_staging = chunked.use_staging = true;
  chunked.staging_chunk_limit = 64 << 10;
  const Mesh mesh = make_bumpy_sphere(5);  // 10K vertices: 328 KB of doubles
  for (Method method : {Method::Exact, Method::Fast}) {
    INFO((method == Method::Exact ? "exact" : "fast"));
    SaliencyOptions o;
    o.method = method;
    const SaliencyResult a = compute_saliency_gpu(whole, mesh, o);
    const uint64_t copies = chunked.staged_copies;
    const SaliencyResult b = compute_saliency_gpu(chunked, mesh, o);
    CHECK(chunked.staged_copies - copies > 5);
    REQUIRE(a.saliency.size() == b.saliency.size());
    CHECK(std::memcmp(a.saliency.data(), b.saliency.data(), 8 * a.saliency.size()) == 0);
  }
}

TEST_CASE("gpu fast saliency: the upload is the float positions and the triangles", "[gpu][fast]") {
  // The doubles and the flags are the device's own now (36 bytes a vertex less): what goes
  // up is 16 bytes a vertex, 12 a triangle and the small tables.
  vk::Context& ctx = context();
  const Mesh mesh = make_bumpy_sphere(4);
  const uint64_t nv = mesh.vertex_count(), nt = mesh.triangle_count();
  SaliencyOptions o;
  o.method = Method::Fast;
  const uint64_t before = ctx.uploaded_bytes;
  const SaliencyResult fast = compute_saliency_gpu(ctx, mesh, o);
  const uint64_t sent = ctx.uploaded_bytes - before;
  INFO(sent << " bytes for " << nv << " vertices, " << nt << " triangles");
  CHECK(sent >= 16 * nv + 12 * nt);
  CHECK(sent < 16 * nv + 12 * nt + 4096);  // the flags alone would be 4 bytes a vertex more
  CHECK(fast.is_point.size() == nv);
  // The exact method still sends its doubles (the curvature from the host in w), flags and 1-rings.
  o.method = Method::Exact;
  const uint64_t exact_before = ctx.uploaded_bytes;
  compute_saliency_gpu(ctx, mesh, o);
  CHECK(ctx.uploaded_bytes - exact_before >= 36 * nv);
}
