// meshsal: device buffers and host transfers (see vk_buffer.h).
#include "gpu/vk_buffer.h"

#include <algorithm>
#include <cstring>
#include <utility>

#include "meshsal/meshsal.h"
#include "gpu/vk_compute.h"

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

// Creates buffer + memory; `storage` adds the storage-buffer usage and its range check.
static void create(Context& ctx, size_t bytes, bool storage, bool host, const std::string& what,
                   VkBuffer* buffer, VkDeviceMemory* memory, void** mapped) {
  if (storage && bytes > ctx.properties.limits.maxStorageBufferRange)
    throw Error("mesh too large for '" + ctx.info.name + "': " + what + " needs " + mib(bytes) +
                ", the device allows " + mib(ctx.properties.limits.maxStorageBufferRange) +
                " per buffer (maxStorageBufferRange); use the CPU path (--backend cpu)");
  VkBufferCreateInfo bi{};
  bi.sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO;
  bi.size = bytes;
  bi.usage = VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT |
             (storage ? VK_BUFFER_USAGE_STORAGE_BUFFER_BIT : 0);
  bi.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
  check(vkCreateBuffer(ctx.device, &bi, nullptr, buffer), "vkCreateBuffer");
  VkMemoryRequirements req;
  vkGetBufferMemoryRequirements(ctx.device, *buffer, &req);
  const VkMemoryPropertyFlags hv =
      VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
  int type = -1;
  bool is_mapped = false;
  if (host) {
    type = find_memory_type(ctx, req.memoryTypeBits, hv | VK_MEMORY_PROPERTY_HOST_CACHED_BIT);
    if (type < 0) type = find_memory_type(ctx, req.memoryTypeBits, hv);
    is_mapped = type >= 0;
  } else {
    // Device-local memory that the host can also see (lavapipe, integrated, resizable BAR)
    // needs no staging copy.
    type = find_memory_type(ctx, req.memoryTypeBits, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT | hv);
    is_mapped = type >= 0;
    if (type < 0) type = find_memory_type(ctx, req.memoryTypeBits, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
    if (type < 0) type = find_memory_type(ctx, req.memoryTypeBits, 0);
  }
  if (type < 0) {
    vkDestroyBuffer(ctx.device, *buffer, nullptr);
    *buffer = VK_NULL_HANDLE;
    throw Error("no suitable Vulkan memory type for " + what);
  }
  VkMemoryAllocateInfo ai{};
  ai.sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO;
  ai.allocationSize = req.size;
  ai.memoryTypeIndex = static_cast<uint32_t>(type);
  VkResult r = vkAllocateMemory(ctx.device, &ai, nullptr, memory);
  if (r != VK_SUCCESS) {
    vkDestroyBuffer(ctx.device, *buffer, nullptr);
    *buffer = VK_NULL_HANDLE;
    if (r == VK_ERROR_OUT_OF_DEVICE_MEMORY || r == VK_ERROR_OUT_OF_HOST_MEMORY)
      throw Error("out of memory on '" + ctx.info.name + "' allocating " + mib(bytes) + " for " +
                  what + "; use the CPU path (--backend cpu)");
    check(r, "vkAllocateMemory");
  }
  check(vkBindBufferMemory(ctx.device, *buffer, *memory, 0), "vkBindBufferMemory");
  *mapped = nullptr;
  if (is_mapped) check(vkMapMemory(ctx.device, *memory, 0, VK_WHOLE_SIZE, 0, mapped), "vkMapMemory");
}

Buffer::Buffer(Context& ctx, size_t bytes, const std::string& what) : ctx_(&ctx) {
  size_ = (std::max<size_t>(bytes, 16) + 15) & ~size_t(15);
  create(ctx, size_, true, false, what, &buffer_, &memory_, &mapped_);
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

// A host-visible transfer buffer, freed at scope exit.
struct Staging {
  Context& ctx;
  VkBuffer buffer = VK_NULL_HANDLE;
  VkDeviceMemory memory = VK_NULL_HANDLE;
  void* mapped = nullptr;
  Staging(Context& c, size_t bytes) : ctx(c) {
    create(ctx, bytes, false, true, "a staging buffer", &buffer, &memory, &mapped);
    if (!mapped) throw Error("no host-visible Vulkan memory for staging");
  }
  ~Staging() {
    VkDevice device = ctx.device;
    VkBuffer b = buffer;
    VkDeviceMemory mem = memory;
    auto destroy = [device, b, mem] {
      vkDestroyBuffer(device, b, nullptr);
      vkFreeMemory(device, mem, nullptr);  // also unmaps
    };
    if (ctx.has_abandoned_work())
      ctx.deferred_destroy.push_back(destroy);
    else
      destroy();
  }
};

void Buffer::upload(const void* data, size_t bytes, size_t offset) {
  if (bytes == 0) return;
  if (offset + bytes > size_) throw Error("internal: upload past the end of a Vulkan buffer");
  if (mapped_) {
    std::memcpy(static_cast<char*>(mapped_) + offset, data, bytes);
    return;
  }
  Staging s(*ctx_, bytes);
  std::memcpy(s.mapped, data, bytes);
  submit(*ctx_, "upload", [&](VkCommandBuffer cmd) {
    VkBufferCopy c{0, offset, bytes};
    vkCmdCopyBuffer(cmd, s.buffer, buffer_, 1, &c);
  });
}

void Buffer::download(void* data, size_t bytes, size_t offset) const {
  if (bytes == 0) return;
  if (offset + bytes > size_) throw Error("internal: download past the end of a Vulkan buffer");
  if (mapped_) {
    std::memcpy(data, static_cast<const char*>(mapped_) + offset, bytes);
    return;
  }
  Staging s(*ctx_, bytes);
  submit(*ctx_, "download", [&](VkCommandBuffer cmd) {
    VkBufferCopy c{offset, 0, bytes};
    vkCmdCopyBuffer(cmd, buffer_, s.buffer, 1, &c);
  });
  std::memcpy(data, s.mapped, bytes);
}

}  // namespace meshsal::vk
