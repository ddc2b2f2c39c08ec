// meshsal: compute pipelines from embedded SPIR-V, descriptor sets, and one command
// submission per stage waited on with a finite fence timeout.
#pragma once
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <utility>
#include <vector>

#include "gpu/vk_buffer.h"
#include "gpu/vk_context.h"

namespace meshsal::vk {

// A compute shader whose bindings 0..n-1 are all storage buffers, plus push constants.
// `specialization` gives the int specialization constants 0..n-1 (the driver compiles
// the shader with them as constants).
class Kernel {
 public:
  Kernel(Context& ctx, const uint32_t* spirv, size_t spirv_bytes, uint32_t bindings,
         uint32_t push_bytes, const char* name, const std::vector<int32_t>& specialization = {});
  ~Kernel();
  Kernel(const Kernel&) = delete;
  Kernel& operator=(const Kernel&) = delete;

  const char* name;
  uint32_t bindings;
  uint32_t push_bytes;
  VkDescriptorSetLayout set_layout = VK_NULL_HANDLE;
  VkPipelineLayout layout = VK_NULL_HANDLE;
  VkPipeline pipeline = VK_NULL_HANDLE;

 private:
  Context& ctx_;
};

// A pool of descriptor sets for one computation; all sets die with it.
class DescriptorPool {
 public:
  DescriptorPool(Context& ctx, uint32_t max_sets, uint32_t max_buffers);
  ~DescriptorPool();
  DescriptorPool(const DescriptorPool&) = delete;
  DescriptorPool& operator=(const DescriptorPool&) = delete;
  // A set for `kernel` with buffers[i] at binding i (whole buffers).
  VkDescriptorSet bind(const Kernel& kernel, const std::vector<const Buffer*>& buffers);

 private:
  Context& ctx_;
  VkDescriptorPool pool_ = VK_NULL_HANDLE;
};

// Records with `record`, closes the command buffer with host_barrier(), submits once and
// waits for the fence at most ctx.fence_timeout_s; a timeout or a lost device becomes an
// Error naming `what`.
void submit(Context& ctx, const char* what, const std::function<void(VkCommandBuffer)>& record);

// submit() in two halves, so that the host can work while the device runs it (the staged
// upload fills one half of its staging area while the other half's copy runs): the
// constructor records and submits, wait() waits as submit() does (and counts the host
// wait). One left unwaited is waited for by its destructor, errors dropped (a timed-out one
// is kept for the context to free, as submit() keeps it).
class PendingSubmission {
 public:
  PendingSubmission() = default;
  PendingSubmission(Context& ctx, const char* what, const std::function<void(VkCommandBuffer)>& record);
  ~PendingSubmission();
  PendingSubmission(PendingSubmission&& o) noexcept { *this = std::move(o); }
  PendingSubmission& operator=(PendingSubmission&& o) noexcept;
  PendingSubmission(const PendingSubmission&) = delete;
  PendingSubmission& operator=(const PendingSubmission&) = delete;
  void wait();  // nothing when nothing is pending

 private:
  void release() noexcept;
  Context* ctx_ = nullptr;
  const char* what_ = "";
  VkFence fence_ = VK_NULL_HANDLE;
  VkCommandBuffer cmd_ = VK_NULL_HANDLE;
};

// Binds the kernel and set, and dispatches groups of `local_size` threads over the items
// [begin, end) (times `groups_y` in y). The push block must begin with two uints
// {base, n}: they are set to the first item of each dispatch and to `end`, so a long range
// is split into several dispatches that stay under maxComputeWorkGroupCount[0].
void dispatch(Context& ctx, VkCommandBuffer cmd, const Kernel& kernel, VkDescriptorSet set,
              void* push, uint32_t begin, uint32_t end, uint32_t local_size,
              uint32_t groups_y = 1);

// The kernel for this SPIR-V on this context, created on first use and kept with the
// context (pipeline creation and the driver's first compile are paid once).
Kernel& cached_kernel(Context& ctx, const uint32_t* spirv, size_t spirv_bytes,
                      uint32_t bindings, uint32_t push_bytes, const char* name,
                      const std::vector<int32_t>& specialization = {});

// The same with the bindings and push block of a shader's interface (gpu/shader_interfaces.h,
// e.g. cached_kernel<shader::GridKey>(ctx, spv_grid_key_comp, sizeof spv_grid_key_comp, "grid_key")).
template <class Shader>
Kernel& cached_kernel(Context& ctx, const uint32_t* spirv, size_t spirv_bytes, const char* name,
                      const std::vector<int32_t>& specialization = {}) {
  return cached_kernel(ctx, spirv, spirv_bytes, Shader::bindings, uint32_t(sizeof(typename Shader::Push)), name,
                       specialization);
}

// Ends every submission: makes its shader and transfer writes visible to the host (the
// Vulkan memory model: a fence wait alone makes them available, not visible) and to the
// shaders and copies of later submissions.
void host_barrier(VkCommandBuffer cmd);
extern std::atomic<uint64_t> host_barriers_recorded;  // how many (tests check submit())

// Makes shader writes (and transfers) before it visible to shader reads/writes after it.
void barrier(VkCommandBuffer cmd);

}  // namespace meshsal::vk
