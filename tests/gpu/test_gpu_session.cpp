// The process-wide Vulkan device cache (gpu/gpu_session.h): the second GPU call on a device
// opens nothing and compiles no pipeline; a busy device gives a private context, not a wait.
#include <catch2/catch.hpp>

#include <algorithm>
#include <string>

#include "api/gpu_backend.h"
#include "api/viewpoint_backend.h"
#include "cli/synthetic.h"
#include "gpu/gpu_saliency.h"
#include "gpu/gpu_session.h"
#include "gpu/vk_context.h"
#include "meshsal/meshsal.h"

using namespace meshsal;

namespace {

bool has_stage(const SaliencyResult& r, const std::string& name) {
  return std::any_of(r.stages.begin(), r.stages.end(),
                     [&](const StageTime& s) { return s.name == name; });
}

SaliencyOptions gpu_options() {
  SaliencyOptions opt;
  opt.backend = Backend::Gpu;
  opt.device = 0;
  return opt;
}

}  // namespace

TEST_CASE("gpu session: the second call opens no device and builds no pipeline", "[gpu]") {
  const uint64_t messages = vk::validation_message_count();
  gpu::release_cached_devices();  // start cold whatever ran before in this process
  const gpu::SessionCounters cold = gpu::session_counters();
  CHECK(cold.cached == 0);

  const SaliencyResult first = compute_saliency(make_bumpy_sphere(3), gpu_options());
  const gpu::SessionCounters after_first = gpu::session_counters();
  CHECK(after_first.contexts_opened == cold.contexts_opened + 1);
  CHECK(after_first.kernels_built > cold.kernels_built);  // the sweep, grid and suppression kernels
  CHECK(after_first.cached == 1);
  CHECK(has_stage(first, "device setup"));

  const Mesh second_mesh = make_sphere(1.0, 3);
  const SaliencyResult second = compute_saliency(second_mesh, gpu_options());
  const gpu::SessionCounters after_second = gpu::session_counters();
  CHECK(after_second.contexts_opened == after_first.contexts_opened);
  CHECK(after_second.kernels_built == after_first.kernels_built);
  CHECK_FALSE(has_stage(second, "device setup"));
  // The cached context computes what a fresh one does.
  vk::Context fresh(0);
  const SaliencyResult own = compute_saliency_gpu(fresh, second_mesh, gpu_options());
  CHECK(own.saliency == second.saliency);

  gpu::release_cached_devices();
  CHECK(gpu::session_counters().cached == 0);
  const SaliencyResult reopened = compute_saliency(second_mesh, gpu_options());
  CHECK(gpu::session_counters().contexts_opened == after_second.contexts_opened + 1);
  CHECK(has_stage(reopened, "device setup"));
  CHECK(reopened.saliency == second.saliency);
  CHECK(vk::validation_message_count() == messages);
}

TEST_CASE("gpu session: a busy device gives the caller a private context", "[gpu]") {
  const Mesh mesh = make_bumpy_sphere(2);
  const SaliencyResult base = compute_saliency(mesh, gpu_options());  // device cached and free
  const gpu::SessionCounters before = gpu::session_counters();
  {
    // A view scorer holds the cached device as long as it lives (the same thread, so
    // waiting for it would never end).
    VisibilityOptions vopt;
    vopt.resolution = 64;
    ViewScorerSetup scorer = make_view_scorer(mesh, base.saliency, vopt, Backend::Gpu, 0);
    CHECK(gpu::session_counters().contexts_opened == before.contexts_opened);
    const SaliencyResult busy = compute_saliency(mesh, gpu_options());
    CHECK(busy.saliency == base.saliency);
    CHECK(has_stage(busy, "device setup"));
    CHECK(gpu::session_counters().contexts_opened == before.contexts_opened + 1);
    CHECK(gpu::session_counters().cached == before.cached);  // the private one is not kept
    CHECK(scorer.scorer({ViewAngles{}}).size() == 1);
  }
  const SaliencyResult again = compute_saliency(mesh, gpu_options());
  CHECK_FALSE(has_stage(again, "device setup"));  // the cached one is free again
  CHECK(gpu::session_counters().contexts_opened == before.contexts_opened + 1);
}

TEST_CASE("gpu session: a device that cannot open is not cached", "[gpu]") {
  const gpu::SessionCounters before = gpu::session_counters();
  SaliencyOptions opt = gpu_options();
  opt.device = 200;
  CHECK_THROWS_WITH(compute_saliency(make_sphere(1.0, 2), opt), Catch::Contains("no Vulkan device 200"));
  CHECK(gpu::session_counters().cached == before.cached);
  CHECK(gpu::session_counters().contexts_opened == before.contexts_opened);
}

#include "test_batch_util.h"

TEST_CASE("gpu session: meshsal batch opens the device and builds its pipelines once", "[gpu][batch]") {
  using namespace meshsal_test;
  const fs::path dir = batch_scratch("gpu");
  const fs::path in = make_batch_inputs(dir), out = dir / "out";
  fs::remove(in / "broken.obj");
  const BatchRun r = run_meshsal("batch " + in.string() + " -o " + out.string() +
                                     " --backend gpu --device 0 --view --size 64 --resolution 32 --restarts 1",
                                 dir);
  INFO(r.err);
  CHECK(r.exit_code == 0);
  CHECK(r.err.find("vulkan validation") == std::string::npos);
  const std::vector<std::string> lines = log_lines(out / "batch.jsonl");
  REQUIRE(lines.size() == 3);
  for (size_t i = 0; i < lines.size(); ++i) {
    INFO(lines[i]);
    CHECK(json_text(lines[i], "status") == "done");
    const size_t view = lines[i].find("\"view\": {");
    REQUIRE(view != std::string::npos);
    CHECK(json_text(lines[i].substr(view), "device").rfind("vulkan: ", 0) == 0);  // the view scorer
    const bool first = i == 0;
    CHECK((lines[i].find("\"device_opened\": true") != std::string::npos) == first);
    CHECK((lines[i].find("\"device_setup\": ") != std::string::npos) == first);
    const size_t at = lines[i].find("\"pipelines_built\": ");
    REQUIRE(at != std::string::npos);
    const long built = std::strtol(lines[i].c_str() + at + 19, nullptr, 10);
    if (first)
      CHECK(built >= 8);  // grid, sweep, suppression and visibility kernels
    else
      CHECK(built == 0);
  }
}

TEST_CASE("gpu session: a warm-up opens the device and builds the run's pipelines ahead", "[gpu]") {
  gpu::release_cached_devices();
  const Mesh mesh = make_bumpy_sphere(3);
  SaliencyOptions o;
  o.backend = Backend::Gpu;
  o.device = 0;
  o.threads = 2;
  // The CPU, tiles or a device that is not there: nothing opened, nothing thrown.
  const gpu::SessionCounters cold = gpu::session_counters();
  SaliencyOptions cpu = o;
  cpu.backend = Backend::Cpu;
  CHECK(warm_up_saliency(cpu).backend == Backend::Cpu);
  SaliencyOptions tiled = o;
  tiled.tiles = 8;
  CHECK(warm_up_saliency(tiled).backend == Backend::Gpu);
  SaliencyOptions missing = o;
  missing.device = 99;
  SaliencyOptions back;
  CHECK_NOTHROW(back = warm_up_saliency(missing));
  CHECK(back.device == 99);  // as given: the run meets the failure
  CHECK(gpu::session_counters().contexts_opened == cold.contexts_opened);
  // Auto resolved as compute_auto resolves it: the hardware GPU, or the CPU where there is
  // none (lavapipe alone): the run then lists the devices no second time.
  SaliencyOptions automatic = o;
  automatic.backend = Backend::Auto;
  automatic.device = -1;
  const SaliencyOptions resolved = warm_up_saliency(automatic);
  const int hardware = pick_hardware_gpu(list_devices());
  if (hardware < 0) {
    CHECK(resolved.backend == Backend::Cpu);
  } else {
    CHECK(resolved.backend == Backend::Auto);
    CHECK(resolved.device == hardware);
  }
  gpu::release_cached_devices();
  for (Method method : {Method::Exact, Method::Fast}) {
    INFO(int(method));
    gpu::release_cached_devices();
    o.method = method;
    const gpu::SessionCounters before = gpu::session_counters();
    warm_up_saliency(o);
    const gpu::SessionCounters warm = gpu::session_counters();
    CHECK(warm.contexts_opened == before.contexts_opened + 1);
    CHECK(warm.kernels_built > before.kernels_built);
    // The run then opens nothing and builds nothing: it starts at once.
    const SaliencyResult r = compute_saliency(mesh, o);
    CHECK_FALSE(has_stage(r, "device setup"));
    CHECK(gpu::session_counters().contexts_opened == warm.contexts_opened);
    CHECK(gpu::session_counters().kernels_built == warm.kernels_built);
    CHECK(r.method == method);
  }
  gpu::release_cached_devices();
}
