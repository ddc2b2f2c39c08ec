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
#include "gpu/vk_context.h"

namespace meshsal {

// Invocations per view for `items` triangles or vertices in a batch of `views` (see
// gpu_visibility.cpp): ~16 items each up to `most` on CPU devices; on GPUs small batches
// get more, so that a batch has about a million invocations.
uint32_t visibility_lanes(uint32_t items, uint32_t most, uint32_t views, bool cpu_device);

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
