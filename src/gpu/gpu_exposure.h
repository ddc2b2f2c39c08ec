// meshsal: exposure (view/exposure.h) on Vulkan, the GPU twin of exposure_cpu. Per batch
// of views: the z-buffers of the viewpoint search (visibility_raster.comp, shared with
// GpuVisibility), then every vertex adds its scores over the batch's views in order
// (shaders/exposure_test.comp) and writes one float; the host adds the batches in double
// and divides by the number of views, as exposure_cpu does.
#pragma once
#include <cstdint>
#include <memory>
#include <vector>

#include "gpu/vk_context.h"
#include "meshsal/meshsal.h"
#include "view/camera.h"
#include "view/exposure.h"

namespace meshsal {

class GpuExposure {
 public:
  // Uploads the mesh, the normals (exposure_normals: 3 floats per vertex) and which
  // vertices are mesh points once. max_batch 0: as many views per submission as keep the
  // z-buffers within 64 MiB (visibility_batch). Throws Error on bad inputs.
  GpuExposure(vk::Context& ctx, const Mesh& mesh, const std::vector<float>& normals, const ViewFrame& frame,
              const VisibilityOptions& options, int max_batch = 0);
  ~GpuExposure();
  GpuExposure(const GpuExposure&) = delete;
  GpuExposure& operator=(const GpuExposure&) = delete;

  // Exposure of every vertex over `views`, the contract of exposure_cpu (0 for vertices
  // that are not mesh points). Throws Error on a device failure.
  std::vector<double> exposure(const std::vector<ViewAngles>& views, ExposureWeighting weighting);

  int batch() const;             // views per submission
  uint64_t submissions() const;  // submissions made so far

 private:
  struct State;
  std::unique_ptr<State> s_;
};

// Invocations of exposure_test.comp for a batch of `views` views: the visibility test's
// plan for the same (vertex, view) pairs, at most one per vertex (see gpu_exposure.cpp).
uint32_t exposure_lanes(uint32_t vertices, uint32_t views, bool cpu_device);

}  // namespace meshsal
