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

void release_cached_devices() {
  if (const GpuBackend* linked = linked_gpu_backend()) linked->release_cached_devices();
}

Device::Device(int index) {
  // The device layer takes any negative index as "choose": -5 would open the best device.
  if (index < -1) throw Error("no Vulkan device " + std::to_string(index) + " (-1 chooses one, else a list_devices() index)");
  handle_ = gpu_backend().open_device(index, &info_);
}

Device::~Device() = default;

// handle_ is read and cleared with the atomic shared_ptr functions: close() from one
// thread while another thread's call takes the handle is safe.
Device::Device(Device&& other) noexcept
    : handle_(std::atomic_exchange(&other.handle_, std::shared_ptr<void>())), info_(std::move(other.info_)) {}

Device& Device::operator=(Device&& other) noexcept {
  if (this != &other) {
    std::atomic_store(&handle_, std::atomic_exchange(&other.handle_, std::shared_ptr<void>()));
    info_ = std::move(other.info_);
  }
  return *this;
}

void Device::close() { std::atomic_store(&handle_, std::shared_ptr<void>()); }

bool Device::is_open() const { return std::atomic_load(&handle_) != nullptr; }

namespace detail {
std::shared_ptr<void> device_handle(const Device& device) { return std::atomic_load(&device.handle_); }
}  // namespace detail

std::shared_ptr<void> session_handle(const Device& session) {
  std::shared_ptr<void> h = detail::device_handle(session);
  if (!h)
    throw Error("the meshsal::Device given (Vulkan device " + std::to_string(session.info().index) + ", '" +
                session.info().name + "') was closed");
  return h;
}

int pick_hardware_gpu(const std::vector<DeviceInfo>& devices) {
  int best = -1, best_rank = 2;
  for (const DeviceInfo& d : devices) {
    const int rank = d.type == "discrete" ? 0 : d.type == "integrated" ? 1 : 2;
    if (d.has_compute && rank < best_rank) best = d.index, best_rank = rank;
  }
  return best;
}

}  // namespace meshsal
