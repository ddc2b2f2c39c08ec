// The Vulkan path against the CPU reference, on lavapipe in CI, with the Khronos validation
// layer on: every raw map, the final saliency and the smoothed saliency must agree per
// vertex to 1e-4 of the map's maximum, and the layer must report nothing.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "gpu/gpu_saliency.h"
#include "meshsal/meshsal.h"
#include "saliency/saliency.h"
#include "cli/synthetic.h"
#include "gpu/vk_context.h"
#include "scoped_value.h"
#include "test_util.h"

using namespace meshsal;

using meshsal_test::check_maps_match;

namespace {

// One validated context for the whole file (the pipelines compile once).
vk::Context& context() {
  static std::unique_ptr<vk::Context> ctx = std::make_unique<vk::Context>(-1, true);
  return *ctx;
}

void compare_once(const Mesh& mesh, SaliencyOptions opt, const std::string& what);

void compare(const Mesh& mesh, SaliencyOptions opt, const std::string& what) {
  // Both sweep variants: the one for this device and the other one (on lavapipe that is
  // the GPU variant, a subgroup per point, which CI could not run otherwise); and both
  // precisions (mixed applies to the default sigmas; other plans run in double).
  for (Precision precision : {Precision::Mixed, Precision::Double})
    for (int variant : {0, 1}) {
      context().sweep_variant = variant;
      INFO("sweep variant " << variant << (precision == Precision::Mixed ? ", mixed" : ", double"));
      opt.precision = precision;
      compare_once(mesh, opt, what);
    }
  context().sweep_variant = -1;
  // The exact method's curvature on the device (lavapipe, a CPU device, takes the host's):
  // in double, the curvature bit for bit and the maps as above.
  if (opt.method != Method::Fast) {
    const meshsal_test::ScopedValue<int> on_device(context().exact_curvature_on_device, 1);
    for (Precision precision : {Precision::Double, Precision::Mixed}) {
      INFO((precision == Precision::Mixed ? "mixed" : "double") << ", the curvature on the device");
      opt.precision = precision;
      compare_once(mesh, opt, what);
    }
  }
}

void compare_once(const Mesh& mesh, SaliencyOptions opt, const std::string& what) {
  INFO(what);
  opt.threads = 2;
  opt.smoothed = true;
  const uint64_t before = vk::validation_message_count();
  SaliencyResult cpu = compute_saliency_cpu(mesh, opt);
  SaliencyResult gpu = compute_saliency_gpu(context(), mesh, opt);
  CHECK(vk::validation_message_count() == before);
  CHECK(gpu.backend_name == context().info.name);
  CHECK(gpu.eps == cpu.eps);
  check_maps_match(cpu, gpu, opt.scales, 1e-4);
  // The host's function or its device twin: the same bits.
  REQUIRE(gpu.curvature.size() == cpu.curvature.size());
  CHECK(std::memcmp(gpu.curvature.data(), cpu.curvature.data(), 8 * cpu.curvature.size()) == 0);
  // Pair counts: identical up to float-vs-double ties at the sweep radius.
  CHECK(cpu.pairs > mesh.vertex_count());
  CHECK(std::fabs(double(gpu.pairs) - double(cpu.pairs)) <= 1e-5 * double(cpu.pairs));
  // Unreferenced vertices stay at zero.
  for (size_t v = 0; v < mesh.vertex_count(); ++v)
    if (!cpu.is_point[v]) {
      CHECK(gpu.saliency[v] == 0);
      CHECK(gpu.smoothed[v] == 0);
    }
}

}  // namespace

TEST_CASE("gpu saliency matches the cpu on synthetic meshes", "[gpu]") {
  SaliencyOptions opt;
  compare(make_bumpy_sphere(4), opt, "bumpy sphere");
  // Symmetry makes exact ties between neighbours, where the strict local-maximum test
  // depends on rounding in any implementation; a tiny deterministic jitter breaks them.
  // (The plane's flat part has curvature 0 up to rounding, so which of its noise-level
  // values are local maxima, and with them m-bar, was down to the last bits of each sum.)
  auto jitter = [](Mesh mesh) {
    for (size_t i = 0; i < mesh.positions.size(); ++i)
      mesh.positions[i] += 1e-4f * float(std::sin(12.9898 * double(i)));
    return mesh;
  };
  compare(jitter(make_plane_with_bump(2.0, 60, 0.3, 0.2)), opt, "jittered plane with bump");
  compare(jitter(make_cube(16)), opt, "jittered cube");
}

TEST_CASE("gpu saliency matches the cpu with other scales and eps", "[gpu]") {
  SaliencyOptions opt;
  opt.scales = {1.5, 3, 7};  // not the default sigma set: the general sweep shader
  opt.eps_frac = 0.005;
  compare(make_bumpy_sphere(3), opt, "bumpy sphere, scales 1.5,3,7");
  opt.scales = {2};
  opt.eps_frac = 0.01;
  compare(make_plane_with_bump(2.0, 40, 0.3, 0.2), opt, "plane, one scale");
}

TEST_CASE("gpu saliency split into many sweep submissions matches the cpu", "[gpu]") {
  // Big scans are swept in slices of the sorted points, one submission each; here a small
  // budget splits a small mesh the same way (slices start mid-row and mid-subgroup).
  context().sweep_pairs_per_submission = 1e4;
  int sweep_submissions = 0;
  SaliencyOptions opt;
  opt.progress = [&](const char* stage, double) {
    sweep_submissions += std::string(stage) == "gaussian sweep";
  };
  compare(make_bumpy_sphere(4), opt, "bumpy sphere, small submissions");
  context().sweep_pairs_per_submission = 0;
  // Both variants ran, each over more than ten slices.
  CHECK(sweep_submissions > 2 * 10);
}

TEST_CASE("gpu saliency keeps unreferenced vertices at zero", "[gpu]") {
  Mesh m = make_bumpy_sphere(3);
  m.positions.insert(m.positions.end(), {0.1f, 0.2f, 0.3f, 5.0f, 5.0f, 5.0f});
  compare(m, SaliencyOptions{}, "bumpy sphere plus two loose vertices");
}

TEST_CASE("gpu saliency matches the cpu on real meshes", "[gpu]") {
  for (const char* name :
       {"bunny_3k.off", "spot_3k.obj", "max_planck_5k.obj", "fandisk_6k.obj", "bunny_36k.obj"}) {
    MESHSAL_MESH_OR_CONTINUE(path, name);
    compare(load_mesh(path), SaliencyOptions{}, name);
  }
}

TEST_CASE("gpu saliency refuses a mesh too large for the device with a clear message", "[gpu]") {
  vk::Context ctx(-1, true);
  ctx.properties.limits.maxStorageBufferRange = 1 << 16;  // 64 KiB per buffer
  Mesh m = make_bumpy_sphere(4);                            // 2.6k vertices: 82 KiB of positions
  CHECK_THROWS_WITH(compute_saliency_gpu(ctx, m, SaliencyOptions{}),
                    Catch::Contains("mesh too large") && Catch::Contains("--backend cpu"));
  ctx.info.device_local_bytes = 1 << 20;  // and a device with 1 MiB of memory
  ctx.properties.limits.maxStorageBufferRange = 1u << 30;
  CHECK_THROWS_WITH(compute_saliency_gpu(ctx, make_bumpy_sphere(5), SaliencyOptions{}),
                    Catch::Contains("mesh too large") && Catch::Contains("MiB of device memory"));
}

TEST_CASE("gpu: without raw_maps the maps are not downloaded, S is the same", "[gpu]") {
  const Mesh mesh = make_bumpy_sphere(3);
  for (Method method : {Method::Exact, Method::Fast}) {
    INFO(int(method));
    SaliencyOptions opt;
    opt.method = method;
    opt.threads = 2;
    opt.smoothed = true;
    const SaliencyResult with = compute_saliency_gpu(context(), mesh, opt);
    opt.raw_maps = false;
    const SaliencyResult without = compute_saliency_gpu(context(), mesh, opt);
    CHECK(with.raw.size() == opt.scales.size());
    CHECK(without.raw.empty());
    CHECK(without.saliency == with.saliency);
    CHECK(without.smoothed == with.smoothed);
    CHECK(without.curvature == with.curvature);
  }
}
