// The two memory paths of the Vulkan layer: mapped unified memory (lavapipe, integrated
// GPUs) and the discrete-GPU path (device-local buffers, copies through the reused staging
// area), which Context::use_staging / MESHSAL_FORCE_STAGING=1 force on any device. Both
// must give the same numbers, and every submission must end with the host barrier.
#include <catch2/catch.hpp>

#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "gpu/gpu_saliency.h"
#include "test_gpu_selftest.h"
#include "test_util.h"
#include "gpu/gpu_visibility.h"
#include "saliency/saliency.h"
#include "cli/synthetic.h"
#include "view/camera.h"
#include "view/viewpoint.h"
#include "view/visibility.h"
#include "gpu/vk_buffer.h"
#include "gpu/vk_compute.h"
#include "gpu/vk_context.h"
#include "gpu/vk_staging.h"

using namespace meshsal;

namespace {

// n words that differ from their neighbours and from 0, so that a misplaced chunk shows.
std::vector<uint32_t> hashed_words(size_t n) {
  std::vector<uint32_t> x(n);
  for (size_t i = 0; i < n; ++i) x[i] = uint32_t(i * 2654435761u);
  return x;
}

}  // namespace

TEST_CASE("forced staging: buffers are unmapped and transfers go through the staging area", "[gpu]") {
  const uint64_t before = vk::validation_message_count();
  {
    vk::Context ctx(-1, true);
    ctx.use_staging = true;
    // More than the largest staging area through one reused area: up in its two halves
    // in turn (three chunks), down in two whole-area chunks.
    const size_t n = vk::kStagingMaxBytes / 4 + 1000;
    const std::vector<uint32_t> x = hashed_words(n);
    std::vector<uint32_t> y(n, 0);
    vk::Buffer b(ctx, n * 4, "test data");
    CHECK(!b.mapped());
    const uint64_t waits = ctx.host_waits;
    b.upload(x.data(), n * 4);
    CHECK(ctx.staged_copies == 3);
    CHECK(ctx.host_waits - waits == 3);  // each copy waited for once
    REQUIRE(ctx.staging);
    CHECK(ctx.staging->size == vk::kStagingMaxBytes);
    const vk::StagingArea* area = ctx.staging.get();
    b.download(y.data(), n * 4);
    CHECK(ctx.staged_copies == 5);
    CHECK(ctx.staging.get() == area);  // reused, not made again
    CHECK(y == x);
    // A range inside the buffer, at an offset.
    std::vector<uint32_t> part(100);
    b.download(part.data(), 400, 4 * (n - 100));
    CHECK(part == std::vector<uint32_t>(x.end() - 100, x.end()));
  }
  CHECK(vk::validation_message_count() == before);
}

TEST_CASE("staged upload_with: the fill writes each chunk at its place, and a failing fill leaves the area usable", "[gpu]") {
  const uint64_t before = vk::validation_message_count();
  vk::Context ctx(-1, true);
  ctx.use_staging = true;
  // Four chunks of half the area, the last one short (a buffer stays under lavapipe's
  // 128 MiB): each fill's bytes depend on where they go.
  const size_t n = 7 * (vk::kStagingMaxBytes / 4) / 8 - 3;
  const size_t offset = 8 * 7;
  vk::Buffer b(ctx, n * 8 + offset, "test data");
  std::vector<size_t> firsts;
  b.upload_with(n * 8, [&](char* to, size_t first, size_t count) {
    firsts.push_back(first);
    for (size_t i = 0; i < count / 8; ++i) {
      const uint64_t value = (first / 8 + i) * 0x9E3779B97F4A7C15ull;
      std::memcpy(to + 8 * i, &value, 8);
    }
  }, offset);
  CHECK(firsts == std::vector<size_t>{0, vk::kStagingMaxBytes / 2, vk::kStagingMaxBytes, 3 * vk::kStagingMaxBytes / 2});
  std::vector<uint64_t> y(n);
  b.download(y.data(), n * 8, offset);
  size_t wrong = 0;
  for (size_t i = 0; i < n; ++i) wrong += y[i] != i * 0x9E3779B97F4A7C15ull;
  CHECK(wrong == 0);
  // A fill that throws in its third chunk: the copies in flight are waited for, the error
  // passes through, and the next upload goes through the same area.
  int calls = 0;
  CHECK_THROWS_WITH(b.upload_with(n * 8, [&](char*, size_t, size_t) {
    if (++calls == 3) throw Error("fill failed");
  }), "fill failed");
  const std::vector<uint64_t> ones(1000, 1);
  b.upload(ones.data(), 8000);
  std::vector<uint64_t> back(1000);
  b.download(back.data(), 8000);
  CHECK(back == ones);
  CHECK(vk::validation_message_count() == before);
}

TEST_CASE("a staged upload whose copy times out with another in flight ends cleanly", "[gpu]") {
  // Copies waited for with a nanosecond's patience: the wait before a half is refilled times
  // out (unless lavapipe was already done, then the data must be right); the other copy in
  // flight is waited for or abandoned, and the context tears down with no validation message.
  const uint64_t before = vk::validation_message_count();
  {
    vk::Context ctx(-1, true);
    ctx.use_staging = true;
    const size_t n = vk::kStagingMaxBytes / 4 + (1 << 20);  // three chunks of half the area
    const std::vector<uint32_t> x = hashed_words(n);
    vk::Buffer b(ctx, n * 4, "test data");
    ctx.fence_timeout_s = 1e-9;
    bool timed_out = false;
    try {
      b.upload(x.data(), n * 4);
    } catch (const Error& e) {
      timed_out = std::string(e.what()).find("did not finish within") != std::string::npos;
      CHECK(timed_out);
    }
    ctx.fence_timeout_s = 60;  // the tear-down's wait (see the time-out test in test_gpu_vulkan.cpp)
    if (timed_out) {
      CHECK(ctx.has_abandoned_work());
    } else {
      std::vector<uint32_t> y(n);
      b.download(y.data(), n * 4);
      CHECK(y == x);
    }
  }
  CHECK(vk::validation_message_count() == before);
}

TEST_CASE("unified memory is mapped, with no staging copies", "[gpu]") {
  vk::Context ctx(-1, true);
  if (!ctx.info.unified_memory) {
    meshsal_test::skip_case("the device has no unified memory");
    return;
  }
  ctx.use_staging = false;
  vk::Buffer b(ctx, 4096, "test data");
  CHECK(b.mapped());
  std::vector<float> x(1000, 2.0f);
  std::vector<float> y = gpu_selftest(ctx, x, 0.5f);
  CHECK(y[999] == 1.0f + 999.0f);
  CHECK(ctx.staged_copies == 0);
  CHECK(!ctx.staging);
}

TEST_CASE("lavapipe reports unified memory, the environment switch forces staging", "[gpu]") {
  auto devices = vk::list_devices();
  for (const auto& d : devices) {
    INFO(d.name);
    if (d.type == "cpu") CHECK(d.unified_memory);
    if (d.type == "discrete") CHECK(!d.unified_memory);
  }
  vk::Context ctx(-1, true);
  CHECK(ctx.use_staging == (!ctx.info.unified_memory || vk::force_staging_by_env()));
}

TEST_CASE("forced staging gives the unified path's saliency bit for bit", "[gpu]") {
  const uint64_t before = vk::validation_message_count();
  Mesh m = make_bumpy_sphere(4);
  SaliencyOptions opt;
  opt.smoothed = true;
  vk::Context mapped(-1, true), staged(-1, true);
  mapped.use_staging = !mapped.info.unified_memory;
  staged.use_staging = true;
  SaliencyResult a = compute_saliency_gpu(mapped, m, opt);
  SaliencyResult b = compute_saliency_gpu(staged, m, opt);
  CHECK(staged.staged_copies >= 6);  // 5 uploads and the downloads at least
  if (mapped.info.unified_memory) CHECK(mapped.staged_copies == 0);
  CHECK(a.saliency == b.saliency);
  CHECK(a.raw == b.raw);
  CHECK(a.smoothed == b.smoothed);
  CHECK(a.pairs == b.pairs);
  CHECK(vk::validation_message_count() == before);
}

TEST_CASE("every submission ends with the barrier that makes its writes visible to the host", "[gpu]") {
  vk::Context ctx(-1, true);
  const uint64_t before = vk::host_barriers_recorded.load();
  int submissions = 0;
  for (int i = 0; i < 3; ++i)
    vk::submit(ctx, "empty", [&](VkCommandBuffer) { ++submissions; });
  CHECK(vk::host_barriers_recorded.load() - before == uint64_t(submissions));
}

TEST_CASE("the memory estimate counts the grid and the staging area", "[gpu]") {
  vk::Context ctx(-1, true);
  Mesh m = make_bumpy_sphere(5);
  // A heap just too small once the grid (8 MiB for 2^20 cells) is counted.
  ctx.info.device_local_bytes = 8u << 20;
  ctx.info.heaps.clear();
  CHECK_THROWS_WITH(compute_saliency_gpu(ctx, m, SaliencyOptions{}),
                    Catch::Contains("MiB of device memory"));
  // A budget below the heap size is what counts (VK_EXT_memory_budget).
  ctx.info.device_local_bytes = 0;
  ctx.info.heaps = {vk::HeapInfo{uint64_t(1) << 34, true, uint64_t(4) << 20}};
  CHECK(vk::device_memory_available(ctx.info) == (uint64_t(4) << 20));
  CHECK_THROWS_WITH(compute_saliency_gpu(ctx, m, SaliencyOptions{}),
                    Catch::Contains("the device has 4 MiB"));
}

TEST_CASE("forced staging: visibility reads back within its own submission, same sums", "[gpu]") {
  const uint64_t before = vk::validation_message_count();
  Mesh m = make_bumpy_sphere(3);
  std::vector<float> w(m.vertex_count(), 1.0f);
  ViewFrame frame = frame_mesh(m);
  VisibilityOptions o;
  o.resolution = 64;
  std::vector<ViewAngles> dirs = fibonacci_directions(40);
  vk::Context mapped(-1, true), staged(-1, true);
  mapped.use_staging = !mapped.info.unified_memory;
  staged.use_staging = true;
  GpuVisibility a(mapped, m, w, frame, o, 16), b(staged, m, w, frame, o, 16);
  const uint64_t copies = staged.staged_copies;  // the mesh and weights uploads
  std::vector<double> ua = a.score(dirs), ub = b.score(dirs);
  CHECK(b.submissions() == 3);
  // Per batch two copies recorded in its own submission (the sums and the status word),
  // no transfer of their own.
  CHECK(staged.staged_copies - copies == 6);
  CHECK(ua == ub);
  CHECK(vk::validation_message_count() == before);
}

TEST_CASE("forced staging: after a timed-out transfer the next one takes a fresh staging area", "[gpu]") {
  const uint64_t before = vk::validation_message_count();
  {
    vk::Context ctx(-1, true);
    ctx.use_staging = true;
    std::vector<float> x(size_t(1) << 20, 1.0f);
    ctx.fence_timeout_s = 1e-9;  // the upload's copy cannot finish in a nanosecond
    CHECK_THROWS_WITH(gpu_selftest(ctx, x, 2.0f), Catch::Contains("did not finish within"));
    REQUIRE(ctx.has_abandoned_work());
    REQUIRE(ctx.staging);
    const VkBuffer old = ctx.staging->buffer;  // not destroyed yet: a new one differs
    ctx.fence_timeout_s = 60;
    std::vector<float> y = gpu_selftest(ctx, x, 2.0f);
    CHECK(ctx.staging->buffer != old);  // the abandoned copy may still use the old one
    CHECK(y[12345] == 2.0f + 12345.0f);
  }  // the context waits (bounded) for the abandoned copy, then frees everything
  CHECK(vk::validation_message_count() == before);
}

TEST_CASE("an allocation larger than what its heap has left is refused clearly", "[gpu]") {
  vk::Context ctx(-1, true);
  for (bool staging : {false, true}) {
    ctx.use_staging = staging;
    ctx.info.has_memory_budget = false;  // the budgets below stand for the extension's
    for (auto& h : ctx.info.heaps) h.budget = uint64_t(1) << 20;
    CHECK_NOTHROW(vk::Buffer(ctx, 512 << 10, "half a MiB"));
    CHECK_THROWS_WITH(vk::Buffer(ctx, 2 << 20, "two MiB"),
                      Catch::Contains("two MiB needs 2 MiB") &&
                          Catch::Contains("its memory heap has 1 MiB left"));
  }
}
