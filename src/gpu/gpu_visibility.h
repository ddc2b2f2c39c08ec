// meshsal: visible score of many views in one Vulkan submission (the GPU twin of
// visible_score_cpu). Per batch of views: fill the z-buffers (one res x res layer per view)
// with +inf, rasterise every (triangle, view) pair in a compute shader with atomicMin on
// the depth bits (shaders/visibility_raster.comp), then test every (vertex, view) pair and
// reduce the visible weights on the device to one value per view and work group
// (shaders/visibility_test.comp); the host adds those few in double. No render pass, no
// images: plain storage buffers.
#pragma once
#include <cstdint>
#include <memory>
#include <vector>

#include "view/camera.h"
#include "meshsal/meshsal.h"
#include "view/visibility.h"
#include "gpu/vk_compute.h"
#include "gpu/vk_context.h"

namespace meshsal {

// Invocations per view for `items` triangles or vertices in a batch of `views` (see
// gpu_visibility.cpp): ~16 items each up to `most` on CPU devices; on GPUs small batches
// get more, so that a batch has about a million invocations.
uint32_t visibility_lanes(uint32_t items, uint32_t most, uint32_t views, bool cpu_device);

// What the GPU exposure (gpu_exposure.h) shares with this path: the batch plan, the z-buffer
// kernel and the loop budget, so that both stay one rule.
constexpr uint32_t kVisibilityViewsPerGroup = 4;  // VIEWS_PER_GROUP in both shaders
constexpr uint32_t kVisibilityRasterMost = 4096, kVisibilityTestMost = 2048;  // invocations per view (CPU plan)
// Lavapipe (gallivm) ends every loop of an invocation, silently, once its loops have taken
// 65535 steps in all. On CPU devices the shaders count their steps and flag an invocation
// that may reach that (a little below, to keep a margin for the loops they do not count).
constexpr uint32_t kCpuLoopBudget = 60000;

// Views per submission at this resolution: as many as keep the z-buffers within 64 MiB
// and the device's limits, at most max_batch when that is > 0. Throws Error when one
// z-buffer passes the device's buffer limit.
int visibility_batch(const vk::Context& ctx, int resolution, int max_batch);

// shaders/visibility_raster.comp on this context (one cached pipeline for every user; its
// bindings: positions, triangles, view rows, z-buffers, status).
vk::Kernel& visibility_raster_kernel(vk::Context& ctx);

// Records the z-buffers of `views` views into `zbuf` (cleared to +inf first) with the
// raster kernel and its set; the status flag must be cleared before and read after.
void record_depth_buffers(vk::Context& ctx, VkCommandBuffer cmd, const vk::Kernel& raster, VkDescriptorSet set,
                          const vk::Buffer& zbuf, uint32_t res, uint32_t triangles, uint32_t views,
                          bool cpu_device);

// Throws the loop-budget Error when `over_budget` (the shaders' status flag) is set.
void check_loop_budget(uint32_t over_budget, const vk::Context& ctx);

class GpuVisibility {
 public:
  // Uploads the mesh and weights (visibility_weights) once. max_batch 0: as many views per
  // submission as keep the z-buffers within 64 MiB (and the device's buffer limit).
  GpuVisibility(vk::Context& ctx, const Mesh& mesh, const std::vector<float>& weights,
                const ViewFrame& frame, const VisibilityOptions& options, int max_batch = 0);
  ~GpuVisibility();
  GpuVisibility(const GpuVisibility&) = delete;
  GpuVisibility& operator=(const GpuVisibility&) = delete;

  // U per view, same definition as visible_score_cpu. Throws Error on a device failure.
  std::vector<double> score(const std::vector<ViewAngles>& views);

  int batch() const;              // views per submission
  uint64_t submissions() const;   // submissions made so far
  uint64_t values_read() const;   // partial sums read back so far (views x work groups)

 private:
  struct State;
  std::unique_ptr<State> s_;
};

}  // namespace meshsal
