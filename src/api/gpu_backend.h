// meshsal: the Vulkan backend's entry points as the rest of the api layer sees them. The
// library a program links decides which backend it has: meshsal::gpu brings
// gpu_backend_vulkan.cpp (the entries call src/gpu), meshsal::core brings
// gpu_backend_none.cpp (no backend: every GPU request is refused with one clear message).
#pragma once
#include <memory>
#include <string>
#include <vector>

#include "meshsal/meshsal.h"
#include "view/exposure.h"
#include "view/viewpoint.h"

namespace meshsal {

// A visibility scorer and what it runs on (see make_view_scorer).
struct ViewScorerSetup {
  ViewScorer scorer;
  std::string backend_name;          // "cpu (N threads)" or "vulkan: <device>"
  int batch = 64;                    // good batch size for exhaustive maps
  std::shared_ptr<void> keep_alive;  // owns the GPU state the scorer uses
};

// Exposure (view/exposure.h) as the GPU computed it, and where.
struct ExposureRun {
  std::vector<double> exposure;
  std::string backend_name;  // "vulkan: <device>"
};

struct GpuBackend {
  std::vector<DeviceInfo> (*list_devices)();
  SaliencyResult (*saliency)(const Mesh& mesh, const SaliencyOptions& options);
  // gpu/gpu_saliency.h's warm_up_saliency_gpu: options.device opened and cached, the run's
  // pipelines compiled and probes run (see warm_up_saliency).
  void (*warm_up)(const SaliencyOptions& options);
  // gpu/gpu_saliency.h's prestage_positions_gpu, prestage_triangles_gpu and
  // drop_prestaged_gpu: a mesh's arrays uploaded ahead of its run (api/read_upload.h).
  bool (*prestage_positions)(const SaliencyOptions& options, const float* positions, size_t vertex_count);
  bool (*prestage_triangles)(const SaliencyOptions& options, const uint32_t* triangles, size_t triangle_count);
  void (*drop_prestaged)(const SaliencyOptions& options);
  ViewScorerSetup (*view_scorer)(const Mesh& mesh, const std::vector<double>& score,
                                 const VisibilityOptions& options, int device);
  // meshsal::Device: opens device `index` (-1: the best) outside the cache and returns its
  // opaque handle (gpu::HeldDevice), filling `info`.
  std::shared_ptr<void> (*open_device)(int index, DeviceInfo* info);
  // The same as saliency and view_scorer, on a handle open_device made.
  SaliencyResult (*saliency_on)(const std::shared_ptr<void>& device, const Mesh& mesh,
                                const SaliencyOptions& options);
  ViewScorerSetup (*view_scorer_on)(const std::shared_ptr<void>& device, const Mesh& mesh,
                                    const std::vector<double>& score, const VisibilityOptions& options);
  // Closes the process-wide cache's devices (gpu::release_cached_devices).
  void (*release_cached_devices)();
  // The GPU twin of exposure_cpu (the same contract) on device `device` (-1: choose), and
  // on a handle open_device made.
  ExposureRun (*exposure)(const Mesh& mesh, const std::vector<float>& normals, const ViewFrame& frame,
                          const std::vector<ViewAngles>& views, ExposureWeighting weighting,
                          const VisibilityOptions& options, int device);
  ExposureRun (*exposure_on)(const std::shared_ptr<void>& device, const Mesh& mesh, const std::vector<float>& normals,
                             const ViewFrame& frame, const std::vector<ViewAngles>& views,
                             ExposureWeighting weighting, const VisibilityOptions& options);
};

// The linked backend, or nullptr in a library without Vulkan (gpu_backend_*.cpp).
const GpuBackend* linked_gpu_backend();

// The open handle of `session` (throws Error when it was closed).
std::shared_ptr<void> session_handle(const Device& session);

// What a saliency run with `options` will pay once per process on a GPU (the device's
// opening, the pipelines' compiles, the probes), paid now on the device that run will take
// (Backend::Gpu: options.device; Auto: the hardware GPU it would pick; nothing for the CPU,
// tiles, a session or a library without Vulkan). Never throws: a failure is left for the
// run to report. For a front end to call on a thread while it reads the input. Returns the
// options with what it resolved for Auto (the GPU's index, or Backend::Cpu where Auto takes
// the CPU), so that the run lists the devices no second time; as given where it resolved
// nothing or failed (the run then meets the failure and says so).
SaliencyOptions warm_up_saliency(const SaliencyOptions& options);

// The linked backend; throws Error when this library has none.
const GpuBackend& gpu_backend();

// Index of the device `auto` picks: the first discrete GPU with compute, else the first
// integrated one; -1 if there is neither (e.g. only lavapipe, a CPU device).
int pick_hardware_gpu(const std::vector<DeviceInfo>& devices);

}  // namespace meshsal
