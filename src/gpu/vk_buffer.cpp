// meshsal: device buffers and host transfers (see vk_buffer.h).
#include "gpu/vk_buffer.h"

#include <algorithm>
#include <cstring>
#include <utility>

#include "meshsal/meshsal.h"
#include "gpu/vk_compute.h"
#include "gpu/vk_staging.h"

namespace meshsal::vk {

int find_memory_type(const Context& ctx, uint32_t type_bits, VkMemoryPropertyFlags flags) {
  for (uint32_t i = 0; i < ctx.memory.memoryTypeCount; ++i)
    if ((type_bits & (1u << i)) && (ctx.memory.memoryTypes[i].propertyFlags & flags) == flags)
      return static_cast<int>(i);
  return -1;
}

static std::string mib(size_t bytes) {
  return std::to_string((bytes + (1u << 20) - 1) >> 20) + " MiB";
}

Allocation allocate_buffer(Context& ctx, size_t bytes, VkBufferUsageFlags usage,
                           std::initializer_list<VkMemoryPropertyFlags> prefer, bool map,
                           const std::string& what) {
  Allocation out;
  VkBufferCreateInfo bi{};
  bi.sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO;
  bi.size = bytes;
  bi.usage = usage;
  bi.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
  check(vkCreateBuffer(ctx.device, &bi, nullptr, &out.buffer), "vkCreateBuffer");
  auto fail = [&](const std::string& message) {
    vkDestroyBuffer(ctx.device, out.buffer, nullptr);
    throw Error(message);
  };
  VkMemoryRequirements req;
  vkGetBufferMemoryRequirements(ctx.device, out.buffer, &req);
  int type = -1;
  for (VkMemoryPropertyFlags flags : prefer)
    if (type < 0) type = find_memory_type(ctx, req.memoryTypeBits, flags);
  if (type < 0) fail("no suitable Vulkan memory type for " + what);
  out.flags = ctx.memory.memoryTypes[type].propertyFlags;
  const uint32_t heap = ctx.memory.memoryTypes[type].heapIndex;
  const uint64_t room = heap_room(ctx, heap);
  if (req.size > room)
    fail("out of memory on '" + ctx.info.name + "': " + what + " needs " + mib(req.size) +
         ", its memory heap has " + mib(room) + " left" + "; use the CPU path (--backend cpu)");
  VkMemoryAllocateInfo ai{};
  ai.sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO;
  ai.allocationSize = req.size;
  ai.memoryTypeIndex = static_cast<uint32_t>(type);
  VkResult r = vkAllocateMemory(ctx.device, &ai, nullptr, &out.memory);
  if (r == VK_ERROR_OUT_OF_DEVICE_MEMORY || r == VK_ERROR_OUT_OF_HOST_MEMORY)
    fail("out of memory on '" + ctx.info.name + "' allocating " + mib(bytes) + " for " + what +
         "; use the CPU path (--backend cpu)");
  if (r != VK_SUCCESS) fail(std::string("vkAllocateMemory failed: ") + result_name(r));
  r = vkBindBufferMemory(ctx.device, out.buffer, out.memory, 0);
  if (r == VK_SUCCESS && map) r = vkMapMemory(ctx.device, out.memory, 0, VK_WHOLE_SIZE, 0, &out.mapped);
  if (r != VK_SUCCESS) {
    vkFreeMemory(ctx.device, out.memory, nullptr);
    fail(std::string("binding or mapping Vulkan memory failed: ") + result_name(r));
  }
  return out;
}

Buffer::Buffer(Context& ctx, size_t bytes, const std::string& what) : ctx_(&ctx) {
  size_ = (std::max<size_t>(bytes, 16) + 15) & ~size_t(15);
  if (size_ > ctx.properties.limits.maxStorageBufferRange)
    throw Error("mesh too large for '" + ctx.info.name + "': " + what + " needs " + mib(size_) +
                ", the device allows " + mib(ctx.properties.limits.maxStorageBufferRange) +
                " per buffer (maxStorageBufferRange); use the CPU path (--backend cpu)");
  const VkBufferUsageFlags usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT |
                                   VK_BUFFER_USAGE_TRANSFER_SRC_BIT |
                                   VK_BUFFER_USAGE_TRANSFER_DST_BIT;
  const VkMemoryPropertyFlags local = VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT;
  const VkMemoryPropertyFlags mappable = local | VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT |
                                         VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
  // Unified memory: mapped device memory, no copies. Otherwise device-local memory that
  // only the staging copies touch (the host never maps it, even where it could).
  Allocation a = ctx.use_staging ? allocate_buffer(ctx, size_, usage, {local, 0}, false, what)
                                 : allocate_buffer(ctx, size_, usage, {mappable, local, 0}, false, what);
  buffer_ = a.buffer;
  memory_ = a.memory;
  if (!ctx.use_staging && (a.flags & mappable) == mappable) {
    VkResult r = vkMapMemory(ctx.device, memory_, 0, VK_WHOLE_SIZE, 0, &mapped_);
    if (r != VK_SUCCESS) {
      release();
      check(r, "vkMapMemory");
    }
  }
}

Buffer Buffer::host_visible(Context& ctx, size_t bytes, const std::string& what) {
  Buffer b;
  b.ctx_ = &ctx;
  b.size_ = (std::max<size_t>(bytes, 16) + 15) & ~size_t(15);
  const VkBufferUsageFlags usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT |
                                   VK_BUFFER_USAGE_TRANSFER_SRC_BIT |
                                   VK_BUFFER_USAGE_TRANSFER_DST_BIT;
  const VkMemoryPropertyFlags host = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT |
                                     VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
  // Cached where the device has it: the host reads these.
  Allocation a = allocate_buffer(ctx, b.size_, usage, {host | VK_MEMORY_PROPERTY_HOST_CACHED_BIT, host},
                                 true, what);
  b.buffer_ = a.buffer;
  b.memory_ = a.memory;
  b.mapped_ = a.mapped;
  return b;
}

Buffer::~Buffer() { release(); }

void Buffer::release() {
  if (!ctx_) return;
  VkDevice device = ctx_->device;
  VkBuffer buffer = buffer_;
  VkDeviceMemory memory = memory_;
  auto destroy = [device, buffer, memory] {
    if (buffer) vkDestroyBuffer(device, buffer, nullptr);
    if (memory) vkFreeMemory(device, memory, nullptr);  // also unmaps
  };
  if (ctx_->has_abandoned_work())
    ctx_->deferred_destroy.push_back(destroy);  // a timed-out submission may still use it
  else
    destroy();
  ctx_ = nullptr;
  buffer_ = VK_NULL_HANDLE;
  memory_ = VK_NULL_HANDLE;
  mapped_ = nullptr;
  size_ = 0;
}

Buffer::Buffer(Buffer&& o) noexcept { *this = std::move(o); }

Buffer& Buffer::operator=(Buffer&& o) noexcept {
  if (this != &o) {
    release();
    std::swap(ctx_, o.ctx_);
    std::swap(buffer_, o.buffer_);
    std::swap(memory_, o.memory_);
    std::swap(mapped_, o.mapped_);
    std::swap(size_, o.size_);
  }
  return *this;
}

void Buffer::upload(const void* data, size_t bytes, size_t offset) {
  upload_with(bytes, copy_from(data, ctx_ ? ctx_->host_threads : 0), offset);
}

void Buffer::upload_with(size_t bytes, const std::function<void(char*, size_t, size_t)>& fill, size_t offset) {
  if (bytes == 0) return;
  if (offset + bytes > size_) throw Error("internal: upload past the end of a Vulkan buffer");
  ctx_->uploaded_bytes += bytes;
  if (mapped_) {
    fill(static_cast<char*>(mapped_) + offset, 0, bytes);
    return;
  }
  staged_upload(*ctx_, buffer_, offset, bytes, fill);
}

void Buffer::download(void* data, size_t bytes, size_t offset) const {
  if (bytes == 0) return;
  if (offset + bytes > size_) throw Error("internal: download past the end of a Vulkan buffer");
  if (mapped_) {
    std::memcpy(data, static_cast<const char*>(mapped_) + offset, bytes);
    return;
  }
  staged_download(*ctx_, buffer_, offset, data, bytes);
}

}  // namespace meshsal::vk
