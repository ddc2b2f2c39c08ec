// meshsal: the process-wide cache of open Vulkan devices, and the devices a caller holds
// itself (meshsal::Device, HeldDevice below), which bypass it. Opening a device (instance,
// driver load, logical device) and compiling the compute pipelines cost far more than a
// small mesh's saliency on lavapipe; a cached vk::Context keeps its compiled kernels
// (kernel_cache), so every GPU call after the first on a device pays neither. Batch runs,
// the Python module and any library user of Backend::Gpu share it, unless the call names
// a meshsal::Device (SaliencyOptions::session): that one runs on the caller's own device,
// and release_cached_devices() (public as meshsal::release_cached_devices) closes the cache.
//
// Thread safety: a context's queue, kernel cache and per-call fields are not thread-safe,
// so a call holds its cached context exclusively (a lease). A call that finds it busy (another
// thread, or a view scorer of the same thread still alive) gets a private context of its
// own for that call instead of waiting: never a deadlock, and threads still run in parallel.
// Bounded: at most kMaxCachedDevices contexts are cached, one per (device index,
// validation, forced staging); their memory is the context, its kernels and its staging
// area (sized by the largest transfer so far); mesh buffers are freed after every call.
#pragma once
#include <cstddef>
#include <cstdint>
#include <memory>
#include <mutex>

#include "gpu/vk_context.h"

namespace meshsal::gpu {

constexpr size_t kMaxCachedDevices = 4;

struct CachedDevice;  // gpu_session.cpp

// Exclusive use of one open device for one call (or one view scorer's life).
class DeviceLease {
 public:
  DeviceLease() = default;
  DeviceLease(DeviceLease&&) noexcept;
  DeviceLease& operator=(DeviceLease&&) noexcept;
  ~DeviceLease();

  vk::Context& context() const;  // (not on an empty lease)
  bool held() const { return cached_ || own_; }
  // True when this lease opened the device (nothing was cached for it, or it was busy):
  // open_seconds() is then the start-up this call paid.
  bool opened() const { return opened_; }
  double open_seconds() const { return open_seconds_; }
  // After a failure: drops the cached context when it may be unusable (work abandoned
  // after a timeout, or a lost device: `error` names VK_ERROR_DEVICE_LOST), so that the
  // next call opens a fresh one.
  void discard_if_broken(const char* error);

 private:
  friend DeviceLease lease_device(int device_index, bool validation);
  friend DeviceLease lease_cached_device(int device_index, bool validation);
  std::shared_ptr<CachedDevice> cached_;
  std::unique_lock<std::mutex> lock_;
  std::unique_ptr<vk::Context> own_;  // a private context (cache busy or full)
  bool opened_ = false;
  double open_seconds_ = 0;
  size_t kernels_at_start_ = 0;
  void release();
};

// A lease on device `device_index` (-1: the best one, as vk::Context). validation: the
// Khronos layer (also on with MESHSAL_VALIDATION=1). Throws Error when the device cannot
// be opened.
DeviceLease lease_device(int device_index, bool validation);

// A lease on the cached context of device `device_index` (keyed as lease_device keys it)
// where it is open and free; an empty lease (held() false) otherwise. For work that only
// pays where the next call will find it (gpu_prestage.h), and that must not open a device.
DeviceLease lease_cached_device(int device_index, bool validation);

// The device a meshsal::Device holds (its opaque handle): opened once, never cached, closed
// when the last holder (the Device, a running call, a view scorer) lets go. A call holds
// `busy` while it uses the context (calls on one device from several threads take turns).
struct HeldDevice {
  explicit HeldDevice(int device_index) : ctx(device_index, vk::validation_requested_by_env()) {}
  std::mutex busy;
  vk::Context ctx;
};

// Process-wide counts, for tests and batch logs.
struct SessionCounters {
  uint64_t contexts_opened = 0;  // vk::Contexts made by lease_device (cached or private)
  uint64_t kernels_built = 0;    // compute pipelines compiled on leased contexts
  size_t cached = 0;             // contexts in the cache now
};
SessionCounters session_counters();

// Closes every cached device that no lease holds (a busy one is closed when its lease
// ends). Also run at exit, before the driver's own tear-down.
void release_cached_devices();

}  // namespace meshsal::gpu
