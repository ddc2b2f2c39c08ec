// meshsal public interface: backends, Vulkan devices and sessions, the C heap policy.
// Part of meshsal.h (which includes every part); the conventions at the top of
// meshsal.h hold for every function here.
#pragma once
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace meshsal {

// ------------------------------------------------------------------------------------------
// Backends

enum class Backend {
  Auto,  // a discrete or integrated GPU when there is one, else the CPU (with a notice on failure)
  Cpu,   // the CPU reference path
  Gpu    // a Vulkan device (Error when built without Vulkan or no device works)
};

// ------------------------------------------------------------------------------------------
// Devices

struct DeviceInfo {
  int index = 0;                    // the `device` option's value for this device
  std::string name;
  std::string type;                 // "discrete", "integrated", "virtual", "cpu", "other"
  uint64_t device_local_bytes = 0;  // largest device-local heap
  std::string api_version;          // "1.3.239"
  bool has_compute = false;         // a queue family with compute
};

// True when this build has the Vulkan backend (linked with meshsal::gpu).
bool built_with_vulkan();

// The Vulkan devices. Throws Error when built without Vulkan or no driver is installed.
std::vector<DeviceInfo> list_devices();

// An open Vulkan device (instance, logical device, compute queue and, as calls use them,
// its compiled kernels and staging area), held by the caller: pass it as
// SaliencyOptions::session or ViewpointOptions::session and every call runs on it without
// opening the device or compiling its kernels again. The device is released when the
// Device is destroyed or closed (a call still running on it, or a view search's scorer,
// keeps it until that call returns). Calls given one Device from several threads run on it
// one at a time (each waits for the previous); calls of one thread must not nest on it (a
// progress callback calling compute_saliency with the same Device waits forever).
//
// Without a session, Backend::Gpu and Backend::Auto use a process-wide cache instead (one
// open device per index, kept until release_cached_devices() or the end of the process):
// the command-line tool relies on it; library callers who want control use a Device.
class Device;

// Names that only the library's own files use: not part of the interface, may change.
namespace detail {
// The open device behind `device`, for the library's backend (opaque here); null once closed.
std::shared_ptr<void> device_handle(const Device& device);
}  // namespace detail

class Device {
 public:
  // Opens device `index` of list_devices(); -1 picks as Backend::Gpu does (the best
  // device: discrete, integrated, virtual, then a CPU device such as lavapipe). Throws Error
  // when built without Vulkan, the index does not exist (below -1, or not listed) or the
  // device cannot be opened.
  explicit Device(int index = -1);
  ~Device();
  Device(Device&& other) noexcept;
  Device& operator=(Device&& other) noexcept;
  Device(const Device&) = delete;
  Device& operator=(const Device&) = delete;

  // What was opened (its `index` is the list_devices() index). Still readable after close().
  const DeviceInfo& info() const { return info_; }
  // Releases the device now (when the calls running on it return). A closed Device given
  // to a call is an Error. Idempotent.
  void close();
  bool is_open() const;

 private:
  friend std::shared_ptr<void> detail::device_handle(const Device& device);
  std::shared_ptr<void> handle_;
  DeviceInfo info_;
};

// Closes the devices the process-wide cache holds (calls without a session opened them);
// one a call is using now closes when that call ends. The next such call opens its device
// again. Does nothing in a build without Vulkan. The cache is also closed at exit.
void release_cached_devices();

// ---------------------------------------------------------------------------------------
// The C heap: a choice for programs, never made by the library itself (it is process-wide).
// ---------------------------------------------------------------------------------------

// A saliency run allocates and frees arrays of tens of MB stage after stage. glibc maps
// each large block afresh and gives it back when freed, so every stage pays the page
// faults again. on = true keeps freed blocks in the heap for the next stage (fewer faults
// and less system time for a little more peak memory; figures in docs/benchmarks.md, "Fast
// mode"): large blocks come from the heap (M_MMAP_MAX 0) and its free top is not given
// back (M_TRIM_THRESHOLD INT_MAX). on = false sets glibc's documented default values
// back (M_MMAP_MAX 65536, M_TRIM_THRESHOLD 128 KiB; glibc's dynamic mmap threshold stays
// off once either was set). Returns false, changing nothing, on other C libraries. The
// meshsal command calls it at start-up; Python programs call meshsal.keep_freed_memory().
bool keep_freed_memory_for_reuse(bool on = true);

}  // namespace meshsal
