#include "api/gpu_backend.h"

namespace meshsal {

const GpuBackend& gpu_backend() {
  const GpuBackend* linked = linked_gpu_backend();
  if (!linked)
    throw Error(
        "meshsal was built without Vulkan here (meshsal::gpu not linked, or MESHSAL_WITH_VULKAN=OFF): "
        "use the cpu backend");
  return *linked;
}

bool built_with_vulkan() { return linked_gpu_backend() != nullptr; }

std::vector<DeviceInfo> list_devices() { return gpu_backend().list_devices(); }

int pick_hardware_gpu(const std::vector<DeviceInfo>& devices) {
  int best = -1, best_rank = 2;
  for (const DeviceInfo& d : devices) {
    const int rank = d.type == "discrete" ? 0 : d.type == "integrated" ? 1 : 2;
    if (d.has_compute && rank < best_rank) best = d.index, best_rank = rank;
  }
  return best;
}

}  // namespace meshsal
