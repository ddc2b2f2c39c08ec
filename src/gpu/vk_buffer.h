// meshsal: storage buffers on a Vulkan device. With unified memory (lavapipe, integrated
// GPUs) a buffer is mapped and transfers are a memcpy; otherwise (discrete GPUs, or
// Context::use_staging forced) it lives in device-local memory and transfers go through
// the context's staging area (vk_staging.h).
#pragma once
#include <cstddef>
#include <cstdint>
#include <functional>
#include <initializer_list>
#include <string>

#include "gpu/vk_context.h"

namespace meshsal::vk {

class Buffer {
 public:
  Buffer() = default;
  // A device-local storage buffer of `bytes` (rounded up to 16; zero is allowed).
  // Throws Error naming `what` when it exceeds maxStorageBufferRange or memory runs out.
  Buffer(Context& ctx, size_t bytes, const std::string& what);
  // A small storage buffer in host memory, mapped on every device: the shaders write it
  // (across the bus on a discrete GPU) and the host reads it after the submission without
  // a copy, e.g. the counts the fast filter reads once per sigma.
  static Buffer host_visible(Context& ctx, size_t bytes, const std::string& what);
  ~Buffer();
  Buffer(Buffer&& o) noexcept;
  Buffer& operator=(Buffer&& o) noexcept;
  Buffer(const Buffer&) = delete;
  Buffer& operator=(const Buffer&) = delete;

  VkBuffer handle() const { return buffer_; }
  size_t size() const { return size_; }
  bool mapped() const { return mapped_ != nullptr; }  // host maps it (no staging copies)

  void upload(const void* data, size_t bytes, size_t offset = 0);
  // An upload of `bytes` that `fill` writes straight into the mapping or the staging area
  // (to, first byte, count: see vk_staging.h's FillBytes), without a host copy first.
  void upload_with(size_t bytes, const std::function<void(char*, size_t, size_t)>& fill, size_t offset = 0);
  void download(void* data, size_t bytes, size_t offset = 0) const;

 private:
  void release();
  Context* ctx_ = nullptr;
  VkBuffer buffer_ = VK_NULL_HANDLE;
  VkDeviceMemory memory_ = VK_NULL_HANDLE;
  void* mapped_ = nullptr;  // persistent mapping when the memory is host-visible+coherent
  size_t size_ = 0;
};

// A new buffer with memory of the first type that has all the flags of one of `prefer`
// (tried in order), mapped persistently when `map`. Throws Error naming `what` when the
// allocation exceeds its heap (or the heap's VK_EXT_memory_budget) or memory runs out.
struct Allocation {
  VkBuffer buffer = VK_NULL_HANDLE;
  VkDeviceMemory memory = VK_NULL_HANDLE;
  void* mapped = nullptr;
  VkMemoryPropertyFlags flags = 0;  // of the memory type taken
};
Allocation allocate_buffer(Context& ctx, size_t bytes, VkBufferUsageFlags usage,
                           std::initializer_list<VkMemoryPropertyFlags> prefer, bool map,
                           const std::string& what);

// Index of a memory type allowed by `type_bits` with all of `flags`, or -1.
int find_memory_type(const Context& ctx, uint32_t type_bits, VkMemoryPropertyFlags flags);

}  // namespace meshsal::vk
