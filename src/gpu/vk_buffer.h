// meshsal: storage buffers on a Vulkan device, with upload/download through a staging
// buffer (or a plain memcpy where device memory is host-visible, as on lavapipe).
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>

#include "gpu/vk_context.h"

namespace meshsal::vk {

class Buffer {
 public:
  Buffer() = default;
  // A device-local storage buffer of `bytes` (rounded up to 16; zero is allowed).
  // Throws Error naming `what` when it exceeds maxStorageBufferRange or memory runs out.
  Buffer(Context& ctx, size_t bytes, const std::string& what);
  ~Buffer();
  Buffer(Buffer&& o) noexcept;
  Buffer& operator=(Buffer&& o) noexcept;
  Buffer(const Buffer&) = delete;
  Buffer& operator=(const Buffer&) = delete;

  VkBuffer handle() const { return buffer_; }
  size_t size() const { return size_; }

  void upload(const void* data, size_t bytes, size_t offset = 0);
  void download(void* data, size_t bytes, size_t offset = 0) const;

 private:
  void release();
  Context* ctx_ = nullptr;
  VkBuffer buffer_ = VK_NULL_HANDLE;
  VkDeviceMemory memory_ = VK_NULL_HANDLE;
  void* mapped_ = nullptr;  // persistent mapping when the memory is host-visible+coherent
  size_t size_ = 0;
};

// Index of a memory type allowed by `type_bits` with all of `flags`, or -1.
int find_memory_type(const Context& ctx, uint32_t type_bits, VkMemoryPropertyFlags flags);

}  // namespace meshsal::vk
