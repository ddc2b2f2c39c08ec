// meshsal::Device (the public header): a Vulkan device the caller opens, passes to calls
// (SaliencyOptions::session, ViewpointOptions::session) and releases; the process-wide
// cache (gpu/gpu_session.h) is neither used nor filled by calls that name one, and
// meshsal::release_cached_devices() empties it.
#include <catch2/catch.hpp>

#include <algorithm>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "cli/synthetic.h"
#include "gpu/gpu_session.h"
#include "gpu/vk_context.h"
#include "meshsal/meshsal.h"

using namespace meshsal;

namespace {

bool has_stage(const SaliencyResult& r, const std::string& name) {
  return std::any_of(r.stages.begin(), r.stages.end(), [&](const StageTime& s) { return s.name == name; });
}

SaliencyOptions gpu_options(Device* session = nullptr) {
  SaliencyOptions opt;
  opt.backend = Backend::Gpu;
  opt.device = 0;
  opt.session = session;
  return opt;
}

}  // namespace

TEST_CASE("device session: opened by index, its info is list_devices' entry", "[gpu]") {
  const std::vector<DeviceInfo> devices = list_devices();
  REQUIRE(!devices.empty());
  Device d(0);
  CHECK(d.is_open());
  CHECK(d.info().index == 0);
  CHECK(d.info().name == devices[0].name);
  CHECK(d.info().type == devices[0].type);
  CHECK(d.info().api_version == devices[0].api_version);
  Device best;  // -1: the device Backend::Gpu picks
  CHECK(best.info().name == vk::Context(-1).info.name);
  CHECK_THROWS_AS(Device(int(devices.size()) + 5), Error);
}

TEST_CASE("device session: calls run on the caller's device, never on the cache", "[gpu]") {
  release_cached_devices();
  const gpu::SessionCounters cold = gpu::session_counters();
  REQUIRE(cold.cached == 0);
  const Mesh mesh = make_bumpy_sphere(3);
  Device d(0);
  const SaliencyResult first = compute_saliency(mesh, gpu_options(&d));
  const SaliencyResult second = compute_saliency(make_sphere(1.0, 3), gpu_options(&d));
  // Opened once, by the Device: no call opened a context or cached one.
  const gpu::SessionCounters after = gpu::session_counters();
  CHECK(after.contexts_opened == cold.contexts_opened);
  CHECK(after.cached == 0);
  CHECK_FALSE(has_stage(first, "device setup"));
  CHECK_FALSE(has_stage(second, "device setup"));
  CHECK(first.backend_name == d.info().name);

  // The same numbers as the cache's path on the same device; that one does fill the cache.
  const SaliencyResult cached = compute_saliency(mesh, gpu_options());
  CHECK(cached.saliency == first.saliency);
  CHECK(gpu::session_counters().cached == 1);
  release_cached_devices();  // the public call empties it
  CHECK(gpu::session_counters().cached == 0);

  // Backend::Auto with a session runs on it, even a CPU device (Auto alone would take the
  // CPU path when lavapipe is the only device).
  SaliencyOptions autom = gpu_options(&d);
  autom.backend = Backend::Auto;
  CHECK(compute_saliency(mesh, autom).backend_name == d.info().name);
  // Backend::Cpu with a session contradicts it.
  SaliencyOptions cpu = gpu_options(&d);
  cpu.backend = Backend::Cpu;
  CHECK_THROWS_WITH(compute_saliency(mesh, cpu), Catch::Contains("session was given with the cpu backend"));
  CHECK(gpu::session_counters().contexts_opened == cold.contexts_opened + 1);  // the cached call's only
}

TEST_CASE("device session: fast method and simplification weights take it too", "[gpu]") {
  release_cached_devices();
  const uint64_t opened = gpu::session_counters().contexts_opened;
  Device d(0);
  const Mesh mesh = make_bumpy_sphere(3);
  SaliencyOptions opt = gpu_options(&d);
  opt.method = Method::Fast;
  CHECK(compute_saliency(mesh, opt).backend_name == d.info().name);
  const SimplificationWeights w = simplification_weights(mesh, SaliencyWeightOptions{}, gpu_options(&d));
  CHECK(w.device == d.info().name);
  CHECK(gpu::session_counters().contexts_opened == opened);
  CHECK(gpu::session_counters().cached == 0);
}

TEST_CASE("device session: the viewpoint search scores on it", "[gpu]") {
  release_cached_devices();
  const uint64_t opened = gpu::session_counters().contexts_opened;
  const Mesh mesh = make_bumpy_sphere(3);
  const std::vector<double> score(mesh.vertex_count(), 1.0);
  Device d(0);
  ViewpointOptions vo;
  vo.backend = Backend::Gpu;
  vo.visibility.resolution = 64;
  vo.optimiser.restarts = 2;
  vo.session = &d;
  const Viewpoint on_session = best_viewpoint(mesh, score, vo);
  CHECK(on_session.backend_name == "vulkan: " + d.info().name);
  CHECK(gpu::session_counters().contexts_opened == opened);
  CHECK(gpu::session_counters().cached == 0);
  vo.session = nullptr;
  vo.device = 0;
  const Viewpoint cached = best_viewpoint(mesh, score, vo);
  CHECK(cached.view.theta == on_session.view.theta);
  CHECK(cached.view.phi == on_session.view.phi);
  vo.session = &d;
  vo.backend = Backend::Cpu;
  CHECK_THROWS_AS(best_viewpoint(mesh, score, vo), Error);
  release_cached_devices();
}

TEST_CASE("device session: close() releases it, a closed one is an Error, moves carry it", "[gpu]") {
  const Mesh mesh = make_sphere(1.0, 2);
  Device d(0);
  std::weak_ptr<void> device = detail::device_handle(d);
  REQUIRE(!device.expired());
  Device moved(std::move(d));
  CHECK_FALSE(d.is_open());
  CHECK(moved.is_open());
  CHECK(detail::device_handle(moved) == device.lock());
  moved.close();
  CHECK_FALSE(moved.is_open());
  CHECK(device.expired());  // nothing else held it: the device is closed
  CHECK(moved.info().index == 0);  // the info stays readable
  CHECK_THROWS_WITH(compute_saliency(mesh, gpu_options(&moved)), Catch::Contains("was closed"));
  moved.close();  // idempotent
  {
    Device scoped(0);
    device = detail::device_handle(scoped);
  }
  CHECK(device.expired());  // the destructor released it
}

TEST_CASE("device session: threads sharing one Device take turns and agree", "[gpu]") {
  Device d(0);
  const Mesh mesh = make_bumpy_sphere(3);
  const SaliencyResult alone = compute_saliency(mesh, gpu_options(&d));
  std::vector<SaliencyResult> results(3);
  std::vector<std::thread> threads;
  for (SaliencyResult& r : results)
    threads.emplace_back([&d, &mesh, &r] { r = compute_saliency(mesh, gpu_options(&d)); });
  for (std::thread& t : threads) t.join();
  for (const SaliencyResult& r : results) CHECK(r.saliency == alone.saliency);
}

TEST_CASE("device session: an index below -1 is refused, not taken for 'choose'", "[device]") {
  // Issue 36: the device layer took any negative index as -1, so Device(-5) opened device 0.
  for (int index : {-2, -5, -2147483647 - 1}) {
    INFO(index);
    try {
      Device d(index);
      FAIL("Device(" << index << ") opened '" << d.info().name << "'");
    } catch (const Error& e) {
      CHECK(std::string(e.what()) == "no Vulkan device " + std::to_string(index) +
                                         " (-1 chooses one, else a list_devices() index)");
    }
  }
}
