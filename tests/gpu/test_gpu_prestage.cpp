// A mesh uploaded ahead of its run (gpu/gpu_prestage.h): taken only where its bytes are
// the run's mesh's, the same S bit for bit either way, nothing held after the run; and a
// run that reads a PLY uploads it while the faces are still read (api/read_upload.h).
#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include "cli/synthetic.h"
#include "gpu/gpu_prestage.h"
#include "gpu/gpu_saliency.h"
#include "gpu/gpu_session.h"
#include "gpu/vk_context.h"
#include "meshsal/meshsal.h"
#include "test_io_util.h"

using namespace meshsal;
using meshsal_test::TempDir;

namespace {

SaliencyOptions gpu_options(Method method) {
  SaliencyOptions o;
  o.backend = Backend::Gpu;
  o.device = 0;
  o.threads = 2;
  o.method = method;
  return o;
}

bool same_bits(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * 8) == 0;
}

// The cached context of device 0 (as a run with gpu_options leases it): its count of
// buffers taken and the bytes it still holds.
struct Held {
  uint64_t taken = 0, bytes = 0;
};
template <typename Body>
void on_device0(Body&& body) {
  gpu::DeviceLease lease = gpu::lease_cached_device(0, false);
  REQUIRE(lease.held());
  body(lease.context());
}
Held held_on_device0() {
  Held h;
  on_device0([&](vk::Context& ctx) {
    h.taken = ctx.prestaged_taken;
    h.bytes = gpu::prestaged_bytes(ctx);
  });
  return h;
}

}  // namespace

TEST_CASE("gpu prestage: an array's key is its bytes, whatever the threads", "[gpu]") {
  std::vector<uint32_t> a(3 * 400000 + 5);  // past one 1 MiB block, with a partial word
  for (size_t i = 0; i < a.size(); ++i) a[i] = uint32_t(i * 2654435761u);
  const uint64_t key = gpu::array_key(a.data(), a.size() * 4, 1);
  CHECK(gpu::array_key(a.data(), a.size() * 4, 2) == key);
  CHECK(gpu::array_key(a.data(), a.size() * 4, 3) == key);
  CHECK(gpu::array_key(a.data(), a.size() * 4 - 1, 2) != key);  // one byte fewer
  a[123456] ^= 1u << 7;                                          // one bit
  CHECK(gpu::array_key(a.data(), a.size() * 4, 2) != key);
  a[123456] ^= 1u << 7;
  std::swap(a[10], a[500000]);  // the same words elsewhere
  CHECK(gpu::array_key(a.data(), a.size() * 4, 2) != key);
  CHECK(gpu::array_key(a.data(), 0, 2) != gpu::array_key(a.data(), 4, 2));
}

TEST_CASE("gpu prestage: a run takes the mesh uploaded ahead, with the same S bits", "[gpu]") {
  gpu::release_cached_devices();
  const Mesh mesh = make_bumpy_sphere(3);
  for (Method method : {Method::Fast, Method::Exact}) {
    INFO(int(method));
    const SaliencyOptions o = gpu_options(method);
    const SaliencyResult plain = compute_saliency(mesh, o);  // opens and caches device 0
    // The exact method takes them where the device computes its curvature.
    on_device0([](vk::Context& ctx) { ctx.exact_curvature_on_device = 1; });
    const SaliencyResult device_h = compute_saliency(mesh, o);
    const Held before = held_on_device0();
    CHECK(before.bytes == 0);
    prestage_positions_gpu(o, mesh.positions.data(), mesh.vertex_count());
    prestage_triangles_gpu(o, mesh.triangles.data(), mesh.triangle_count());
    // (each buffer rounded up to 16 bytes, as vk::Buffer makes it)
    CHECK(held_on_device0().bytes == mesh.vertex_count() * 16 + ((mesh.triangle_count() * 12 + 15) & ~size_t(15)));
    const SaliencyResult ahead = compute_saliency(mesh, o);
    const Held after = held_on_device0();
    CHECK(after.taken == before.taken + 2);
    CHECK(after.bytes == 0);
    CHECK(same_bits(ahead.saliency, device_h.saliency));
    CHECK(same_bits(ahead.curvature, device_h.curvature));
    CHECK(same_bits(ahead.saliency, plain.saliency));  // and the host's curvature (exact)
    on_device0([](vk::Context& ctx) { ctx.exact_curvature_on_device = -1; });
  }
  gpu::release_cached_devices();
}

TEST_CASE("gpu prestage: what the run's mesh does not match is uploaded afresh and freed", "[gpu]") {
  gpu::release_cached_devices();
  const SaliencyOptions o = gpu_options(Method::Fast);
  Mesh mesh = make_bumpy_sphere(3);
  compute_saliency(mesh, o);  // device 0 cached
  prestage_positions_gpu(o, mesh.positions.data(), mesh.vertex_count());
  prestage_triangles_gpu(o, mesh.triangles.data(), mesh.triangle_count());
  mesh.positions[3 * 100 + 1] = std::nextafter(mesh.positions[3 * 100 + 1], 2.0f);  // one coordinate, one ulp
  const Held before = held_on_device0();
  const SaliencyResult ahead = compute_saliency(mesh, o);
  const Held after = held_on_device0();
  CHECK(after.taken == before.taken + 1);  // the triangles alone
  CHECK(after.bytes == 0);                 // the stale positions freed
  gpu::release_cached_devices();
  CHECK(same_bits(ahead.saliency, compute_saliency(mesh, o).saliency));
  // Nothing is uploaded ahead where no device is cached (a warm-up opens it): none opened.
  const gpu::SessionCounters cold = gpu::session_counters();
  prestage_positions_gpu(o, mesh.positions.data(), mesh.vertex_count());
  CHECK(gpu::session_counters().contexts_opened == cold.contexts_opened);
  gpu::release_cached_devices();
}

TEST_CASE("gpu prestage: a run reading a PLY uploads it while reading, with the same S bits", "[gpu]") {
  gpu::release_cached_devices();
  const TempDir dir;
  const Mesh sphere = make_bumpy_sphere(3);
  write_mesh(dir.file("sphere.ply"), sphere);
  write_mesh(dir.file("sphere.obj"), sphere);
  for (const char* input : {"sphere.ply", "sphere.obj"}) {
    const Mesh read = load_mesh(dir.file(input));
    for (Method method : {Method::Fast, Method::Exact}) {
      INFO(input << " " << int(method));
      Request r;
      r.input = dir.file(input);
      r.saliency = gpu_options(method);
      r.saliency_output = dir.file("out.ply");
      // The first run opens the device (its warm-up); the counts are of the second.
      run_request(r);
      const Held before = held_on_device0();
      const RequestResult result = run_request(r);
      const Held after = held_on_device0();
      // Taken where the run uploads them (the fast method; on a CPU device the exact one
      // computes its curvature on the host) and the reader tells of them (PLY).
      const bool ply = std::string(input) == "sphere.ply";
      const bool cpu_device = result.saliency.backend_name.find("llvmpipe") != std::string::npos;
      const bool ahead = ply && (method == Method::Fast || !cpu_device);
      CHECK(after.taken - before.taken == (ahead ? 2 : 0));
      CHECK(after.bytes == 0);
      // The result says how long it took, apart from the stages (the read hid most of it);
      // what the read did not hide is the warm-up's wait.
      CHECK((result.upload_while_reading > 0) == ahead);
      REQUIRE_FALSE(result.saliency.stages.empty());
      CHECK(result.saliency.stages[0].name == "device warm-up");
      CHECK(same_bits(result.saliency.saliency, compute_saliency(read, r.saliency).saliency));
    }
  }
  gpu::release_cached_devices();
}
