// The Vulkan layer on its own: device listing, a validated trivial kernel (with a dispatch
// split over maxComputeWorkGroupCount), and clear errors for bad device choices.
#include <catch2/catch.hpp>

#include <string>
#include <vector>

#include "meshsal/meshsal.h"
#include "gpu/gpu_saliency.h"
#include "test_gpu_selftest.h"
#include "gpu/vk_context.h"

using namespace meshsal;

TEST_CASE("vulkan devices are listed with name, type and memory", "[gpu]") {
  auto devices = vk::list_devices(true);
  REQUIRE(!devices.empty());  // CI has lavapipe at least
  for (size_t i = 0; i < devices.size(); ++i) {
    CHECK(devices[i].index == int(i));
    CHECK(!devices[i].name.empty());
    CHECK(!devices[i].type.empty());
  }
  bool has_compute = false;
  for (const auto& d : devices) has_compute = has_compute || d.has_compute;
  CHECK(has_compute);
  // auto never picks a CPU implementation such as lavapipe
  int hw = vk::pick_hardware_gpu(devices);
  if (hw >= 0) CHECK((devices[hw].type == "discrete" || devices[hw].type == "integrated"));
}

TEST_CASE("vulkan self-test kernel matches the CPU under validation", "[gpu]") {
  const uint64_t before = vk::validation_message_count();
  {
    vk::Context ctx(-1, true);
    REQUIRE(ctx.validation);
    // More items than one dispatch may cover (65535 groups of 64), so the split is used.
    const size_t n = size_t(65535) * 64 + 1000;
    std::vector<float> x(n);
    for (size_t i = 0; i < n; ++i) x[i] = float(i % 1000) * 0.5f;
    std::vector<float> y = gpu_selftest(ctx, x, 3.0f);
    REQUIRE(y.size() == n);
    size_t bad = 0;
    for (size_t i = 0; i < n; ++i)
      if (y[i] != 3.0f * x[i] + float(i)) ++bad;
    CHECK(bad == 0);
    CHECK(y[n - 1] == 3.0f * x[n - 1] + float(n - 1));
  }
  CHECK(vk::validation_message_count() == before);
}

TEST_CASE("a vulkan device index out of range is a clear error", "[gpu]") {
  try {
    vk::Context ctx(999, true);
    FAIL("expected an error");
  } catch (const Error& e) {
    CHECK(std::string(e.what()).find("no Vulkan device 999") != std::string::npos);
  }
}

TEST_CASE("a submission past the fence time-out is an error, not a hang", "[gpu]") {
  const uint64_t before = vk::validation_message_count();
  {
    vk::Context ctx(-1, true);
    ctx.fence_timeout_s = 1e-9;  // nothing real finishes in a nanosecond
    std::vector<float> x(size_t(1) << 22, 1.0f);
    bool timed_out = false;
    try {
      gpu_selftest(ctx, x, 2.0f);
    } catch (const Error& e) {
      timed_out = std::string(e.what()).find("did not finish within") != std::string::npos;
    }
    CHECK(timed_out);
    CHECK(ctx.has_abandoned_work());
    // The destructor waits for abandoned work up to max(fence_timeout_s, 1 s). On a loaded
    // machine (or under the sanitizers) lavapipe can need more than 1 s for 16 MiB; this
    // test checks the clean tear-down, not the time-out a hung GPU gets.
    ctx.fence_timeout_s = 60;
  }  // the context waits for the abandoned work, then frees everything cleanly
  CHECK(vk::validation_message_count() == before);
}

TEST_CASE("buffers larger than maxStorageBufferRange are refused clearly", "[gpu]") {
  vk::Context ctx(-1, true);
  ctx.properties.limits.maxStorageBufferRange = 1 << 16;  // pretend a small device
  std::vector<float> x(1 << 15, 1.0f);                     // 128 KiB
  CHECK_THROWS_WITH(gpu_selftest(ctx, x, 1.0f), Catch::Contains("maxStorageBufferRange"));
}
