// meshsal: the library's backend switch (api/gpu_backend.h) in a build with Vulkan: its
// entries call the Vulkan layer (src/gpu). This file goes into meshsal::gpu only;
// meshsal::core gets gpu_backend_none.cpp instead, so which backend a program has is
// decided by the library it links, with no registration at start-up.
#include "api/gpu_backend.h"
#include "gpu/gpu_exposure.h"
#include "gpu/gpu_saliency.h"
#include "gpu/gpu_session.h"
#include "gpu/gpu_visibility.h"
#include "gpu/vk_context.h"

namespace meshsal {
namespace {

DeviceInfo public_info(const vk::DeviceInfo& d) {
  DeviceInfo p;
  p.index = d.index;
  p.name = d.name;
  p.type = d.type;
  p.device_local_bytes = d.device_local_bytes;
  p.api_version = d.api_version;
  p.has_compute = d.has_compute;
  return p;
}

std::vector<DeviceInfo> devices() {
  std::vector<DeviceInfo> out;
  for (const vk::DeviceInfo& d : vk::list_devices()) out.push_back(public_info(d));
  return out;
}

SaliencyResult saliency(const Mesh& mesh, const SaliencyOptions& options) {
  return compute_saliency_gpu(mesh, options);
}

ViewScorerSetup view_scorer(const Mesh& mesh, const std::vector<double>& score,
                            const VisibilityOptions& options, int device) {
  // The scorer holds the process's cached device (gpu_session.h) for as long as it lives:
  // the device and its pipelines are opened and compiled once per process, not per mesh.
  struct Gpu {
    gpu::DeviceLease lease;
    std::unique_ptr<GpuVisibility> vis;  // destroyed before the lease ends
  };
  auto g = std::make_shared<Gpu>();
  g->lease = gpu::lease_device(device, vk::validation_requested_by_env());
  vk::Context& ctx = g->lease.context();
  g->vis = std::make_unique<GpuVisibility>(ctx, mesh, visibility_weights(mesh, score),
                                           frame_mesh(mesh), options);
  ViewScorerSetup s;
  Gpu* raw = g.get();  // kept alive by s.keep_alive
  s.scorer = [raw](const std::vector<ViewAngles>& views) {
    try {
      return raw->vis->score(views);
    } catch (const std::exception& e) {
      raw->lease.discard_if_broken(e.what());
      throw;
    }
  };
  s.backend_name = "vulkan: " + ctx.info.name;
  s.batch = raw->vis->batch();
  s.keep_alive = g;
  return s;
}

std::shared_ptr<void> open_device(int index, DeviceInfo* info) {
  auto held = std::make_shared<gpu::HeldDevice>(index);
  *info = public_info(held->ctx.info);
  return held;
}

SaliencyResult saliency_on(const std::shared_ptr<void>& device, const Mesh& mesh, const SaliencyOptions& options) {
  auto* held = static_cast<gpu::HeldDevice*>(device.get());
  std::lock_guard<std::mutex> busy(held->busy);
  return compute_saliency_gpu(held->ctx, mesh, options);
}

ViewScorerSetup view_scorer_on(const std::shared_ptr<void>& device, const Mesh& mesh,
                               const std::vector<double>& score, const VisibilityOptions& options) {
  // The scorer holds the caller's device (and its lock) for as long as it lives.
  struct Gpu {
    std::shared_ptr<gpu::HeldDevice> held;
    std::unique_lock<std::mutex> busy;
    std::unique_ptr<GpuVisibility> vis;  // destroyed before the lock and the device
  };
  auto g = std::make_shared<Gpu>();
  g->held = std::static_pointer_cast<gpu::HeldDevice>(device);
  g->busy = std::unique_lock<std::mutex>(g->held->busy);
  vk::Context& ctx = g->held->ctx;
  g->vis = std::make_unique<GpuVisibility>(ctx, mesh, visibility_weights(mesh, score), frame_mesh(mesh), options);
  ViewScorerSetup s;
  Gpu* raw = g.get();  // kept alive by s.keep_alive
  s.scorer = [raw](const std::vector<ViewAngles>& views) { return raw->vis->score(views); };
  s.backend_name = "vulkan: " + ctx.info.name;
  s.batch = raw->vis->batch();
  s.keep_alive = g;
  return s;
}

ExposureRun exposure(const Mesh& mesh, const std::vector<float>& normals, const ViewFrame& frame,
                     const std::vector<ViewAngles>& views, ExposureWeighting weighting,
                     const VisibilityOptions& options, int device) {
  // One call on the process's cached device (gpu_session.h), as view_scorer's lease.
  gpu::DeviceLease lease = gpu::lease_device(device, vk::validation_requested_by_env());
  vk::Context& ctx = lease.context();
  try {
    GpuExposure gpu(ctx, mesh, normals, frame, options);
    return {gpu.exposure(views, weighting), "vulkan: " + ctx.info.name};
  } catch (const std::exception& e) {
    lease.discard_if_broken(e.what());
    throw;
  }
}

ExposureRun exposure_on(const std::shared_ptr<void>& device, const Mesh& mesh, const std::vector<float>& normals,
                        const ViewFrame& frame, const std::vector<ViewAngles>& views, ExposureWeighting weighting,
                        const VisibilityOptions& options) {
  auto* held = static_cast<gpu::HeldDevice*>(device.get());
  std::lock_guard<std::mutex> busy(held->busy);
  GpuExposure gpu(held->ctx, mesh, normals, frame, options);
  return {gpu.exposure(views, weighting), "vulkan: " + held->ctx.info.name};
}

const GpuBackend backend{devices,
                         saliency,
                         warm_up_saliency_gpu,
                         prestage_positions_gpu,
                         prestage_triangles_gpu,
                         drop_prestaged_gpu,
                         view_scorer,
                         open_device,
                         saliency_on,
                         view_scorer_on,
                         gpu::release_cached_devices,
                         exposure,
                         exposure_on};

}  // namespace

const GpuBackend* linked_gpu_backend() { return &backend; }

}  // namespace meshsal
