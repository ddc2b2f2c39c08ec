// meshsal: a small Vulkan layer over the plain C API: instance, device choice, one compute
// queue, optional Khronos validation that counts its messages (the tests fail on any).
#pragma once
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <vulkan/vulkan.h>

namespace meshsal::vk {

class Kernel;  // vk_compute.h

// One memory heap of a device.
struct HeapInfo {
  uint64_t bytes = 0;
  bool device_local = false;
  // VK_EXT_memory_budget: what this process may use of the heap (its own use included)
  // when the device was described; 0 unknown.
  uint64_t budget = 0;
};

// One physical device as `meshsal devices` lists it.
struct DeviceInfo {
  int index = 0;                  // position in vkEnumeratePhysicalDevices order
  std::string name;
  std::string type;               // "discrete", "integrated", "virtual", "cpu", "other"
  VkPhysicalDeviceType vk_type = VK_PHYSICAL_DEVICE_TYPE_OTHER;
  uint64_t device_local_bytes = 0;  // largest device-local heap
  std::string api_version;        // "1.3.239"
  bool has_compute = false;       // a queue family with compute
  uint32_t subgroup_size = 0;     // lanes per subgroup (0: Vulkan 1.0 device)
  bool has_float64 = false;       // shaderFloat64
  uint64_t max_storage_buffer = 0;  // maxStorageBufferRange
  std::vector<HeapInfo> heaps;
  bool has_memory_budget = false;   // VK_EXT_memory_budget
  // Unified memory: an integrated or CPU device with a device-local memory type the host
  // maps coherently, so buffers are mapped and no staging copies are needed. Discrete GPUs
  // (even with resizable BAR) keep buffers in device memory the host does not map.
  bool unified_memory = false;
};

// True when MESHSAL_FORCE_STAGING is set to something other than "" or "0": the
// discrete-GPU memory path (device-local buffers, copies through a staging area) on any
// device, so that lavapipe tests it.
bool force_staging_by_env();

// The bytes a device-local allocation may still take: the smallest of the largest
// device-local heap and its VK_EXT_memory_budget budget (when the device reports one).
uint64_t device_memory_available(const DeviceInfo& info);

class StagingArea;  // vk_staging.h

// True when MESHSAL_VALIDATION is set to something other than "" or "0".
bool validation_requested_by_env();

// Number of validation warnings + errors reported so far in this process (all contexts).
uint64_t validation_message_count();

// The devices of the Vulkan loader; throws Error when there is no loader/driver at all.
std::vector<DeviceInfo> list_devices(bool validation = false);

// Index of the device `auto` picks: the first discrete GPU with compute, else the first
// integrated one; -1 if there is neither (e.g. only lavapipe).
int pick_hardware_gpu(const std::vector<DeviceInfo>& devices);

// An open device with one compute queue. Not copyable; destroys everything it made.
class Context {
 public:
  // device_index -1: the best device (discrete > integrated > virtual > cpu).
  // validation: enable VK_LAYER_KHRONOS_validation (also on when MESHSAL_VALIDATION=1);
  // throws Error when requested but not installed.
  explicit Context(int device_index = -1, bool validation = false);
  ~Context();
  Context(const Context&) = delete;
  Context& operator=(const Context&) = delete;

  VkInstance instance = VK_NULL_HANDLE;
  VkPhysicalDevice physical = VK_NULL_HANDLE;
  VkDevice device = VK_NULL_HANDLE;
  VkQueue queue = VK_NULL_HANDLE;
  uint32_t queue_family = 0;
  VkCommandPool command_pool = VK_NULL_HANDLE;
  VkPhysicalDeviceProperties properties{};
  VkPhysicalDeviceMemoryProperties memory{};
  DeviceInfo info;
  bool validation = false;
  bool has_float64 = false;  // shaderFloat64, enabled when the device has it
  uint32_t subgroup_size = 0;        // lanes per subgroup (Vulkan 1.1)
  bool subgroup_arithmetic = false;  // subgroupAdd & co. in compute shaders
  // The sweep variant of the default plan (sweep.glsl): 0 shared rows (a lane per point
  // over rows shared by the subgroup), 1 a subgroup per point; -1: rows on CPU devices, on
  // GPUs as measured_sweep_variant says. Tests run both.
  int sweep_variant = -1;
  // A GPU's choice for -1: both layouts timed once per context (gpu_layout_probe.h), in
  // double ([0]) and mixed ([1]) precision; -1 until then.
  int measured_sweep_variant[2] = {-1, -1};
  // Where the exact method's curvature runs (gpu_curvature.h's input order): 1 on the
  // device, 0 on the host; -1: on GPUs the device, on CPU devices the host
  // (lavapipe on 2 cores took 0.19-0.23 s for igea_134k where the host took 0.03 s). Tests
  // set 1.
  int exact_curvature_on_device = -1;
  // Time of double over float arithmetic, measured on first need (gpu_fp64_rate.h); 0:
  // not yet. Tests may set it to choose what --precision auto takes.
  double fp64_slowdown = 0;
  // Candidate pairs per sweep submission; 0: sized by time (submission_target_s, see
  // gpu_slices.h). Tests set it small to split a small mesh.
  double sweep_pairs_per_submission = 0;
  // Candidates a fast-method query visits per dispatch (gpu_fast.h): lavapipe ends an
  // invocation's loops after 65,535 steps. Tests lower it to split every query into many
  // windows.
  uint32_t fast_window_candidates = 32768;
  double fence_timeout_s = 300;  // a submission that takes longer is an Error (no hang)
  // Buffers live in device-local memory and transfers go through the staging area: on
  // devices without unified memory, or when forced (MESHSAL_FORCE_STAGING=1, or set
  // before any buffer is made). Otherwise buffers are mapped and copied with memcpy.
  bool use_staging = false;
  std::unique_ptr<StagingArea> staging;  // made on first use, reused (vk_staging.h)
  uint64_t staged_copies = 0;            // copy submissions through it (tests count them)
  uint64_t uploaded_bytes = 0;           // bytes Buffer::upload sent (staged or mapped)
  // Host threads for the copies and packing of uploads: the run's --threads (0: the
  // process's share of the cores). compute_saliency_gpu sets it to its options' threads.
  unsigned host_threads = 0;
  // Tests: a staged upload's chunks made at most this (a power of two from 64 KiB; 0: half
  // the staging area), so that a small mesh's upload takes several.
  size_t staging_chunk_limit = 0;
  // Target device time of one sweep submission (seconds): the first slice is timed and
  // the rest sized to it, far below a desktop driver's ~2 s watchdog.
  double submission_target_s = 0.15;
  uint64_t sweep_slices = 0;     // submissions of the last sweep
  double sweep_longest_s = 0;    // and the longest of them (host time, waits included)
  // Submissions the host waited for (vk::submit, staged copies included): each is a
  // round trip the device idles through. The fast filter's phases count theirs.
  uint64_t host_waits = 0;
  // Each phase of the last fast filter (gpu_fast.h), summed over its sigmas, in the order
  // first seen: its host seconds and host waits (tools/bench_gpu_sweep.cpp prints them).
  struct FastPhase {
    std::string name;
    double seconds = 0;
    uint64_t waits = 0;
  };
  std::vector<FastPhase> fast_phases;
  // The fast filter submits its phases separately, so that each one's seconds are its own
  // (the bench sets it); otherwise a sigma's finish and the next one's preparation ride on
  // its last submission of queries.
  bool fast_phase_timing = false;
  std::map<std::string, std::unique_ptr<Kernel>> kernel_cache;  // see cached_kernel()
  // Buffers uploaded ahead of the call that takes them (gpu_prestage.h, which alone knows
  // what it holds: a mesh put on the device while its file is still read), and how many
  // a call took; freed with the context, before its device.
  std::shared_ptr<void> prestaged;
  uint64_t prestaged_taken = 0;
  // Fences and command buffers of submissions that timed out: the device may still use
  // them, so they are freed only once the destructor has seen their fences signal.
  std::vector<VkFence> abandoned_fences;
  std::vector<VkCommandBuffer> abandoned_commands;
  // While work is abandoned, buffers and descriptor pools are destroyed here, later.
  std::vector<std::function<void()>> deferred_destroy;
  bool has_abandoned_work() const { return !abandoned_fences.empty(); }

 private:
  VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
};

// Bytes of memory heap `heap` this process may still allocate: the heap size, or with
// VK_EXT_memory_budget the current budget less the current use (asked afresh each time).
uint64_t heap_room(const Context& ctx, uint32_t heap);

// Throws Error("<what>: <VkResult name>") unless r is VK_SUCCESS.
void check(VkResult r, const char* what);
const char* result_name(VkResult r);

}  // namespace meshsal::vk
