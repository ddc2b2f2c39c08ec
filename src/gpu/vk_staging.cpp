// meshsal: the staging area and the copies through it (see vk_staging.h).
#include "gpu/vk_staging.h"

#include <algorithm>
#include <cstring>

#include "meshsal/meshsal.h"
#include "gpu/vk_buffer.h"
#include "gpu/vk_compute.h"
#include "core/parallel.h"

namespace meshsal::vk {

StagingArea::StagingArea(Context& ctx, size_t bytes) : ctx_(ctx) {
  const VkMemoryPropertyFlags visible = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT;
  const VkMemoryPropertyFlags cached = visible | VK_MEMORY_PROPERTY_HOST_CACHED_BIT;
  const VkMemoryPropertyFlags kept = VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
  // Host-cached first: read-back from uncached (write-combined) memory is very slow.
  Allocation a = allocate_buffer(
      ctx, bytes, VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
      {cached | kept, cached, visible | kept, visible}, true, "the staging area");
  buffer = a.buffer;
  memory_ = a.memory;
  mapped = static_cast<char*>(a.mapped);
  size = bytes;
  coherent = (a.flags & VK_MEMORY_PROPERTY_HOST_COHERENT_BIT) != 0;
}

StagingArea::~StagingArea() {
  // Only ever used by submissions that were waited for, or by an abandoned one: then the
  // context defers (or skips) destruction like its other resources.
  VkDevice device = ctx_.device;
  VkBuffer b = buffer;
  VkDeviceMemory m = memory_;
  auto destroy = [device, b, m] {
    vkDestroyBuffer(device, b, nullptr);
    vkFreeMemory(device, m, nullptr);  // also unmaps
  };
  if (ctx_.has_abandoned_work())
    ctx_.deferred_destroy.push_back(destroy);
  else
    destroy();
}

void StagingArea::flush_host_writes() const {
  if (coherent) return;
  VkMappedMemoryRange r{VK_STRUCTURE_TYPE_MAPPED_MEMORY_RANGE, nullptr, memory_, 0, VK_WHOLE_SIZE};
  check(vkFlushMappedMemoryRanges(ctx_.device, 1, &r), "vkFlushMappedMemoryRanges");
}

void StagingArea::flush_host_writes(size_t offset, size_t bytes) const {
  if (coherent || bytes == 0) return;
  const VkDeviceSize atom = std::max<VkDeviceSize>(1, ctx_.properties.limits.nonCoherentAtomSize);
  const VkDeviceSize begin = offset / atom * atom;
  const VkDeviceSize end = (offset + bytes + atom - 1) / atom * atom;
  // A range reaching the end of the memory must be VK_WHOLE_SIZE or end on an atom.
  const VkDeviceSize range = end >= size ? VK_WHOLE_SIZE : end - begin;
  VkMappedMemoryRange r{VK_STRUCTURE_TYPE_MAPPED_MEMORY_RANGE, nullptr, memory_, begin, range};
  check(vkFlushMappedMemoryRanges(ctx_.device, 1, &r), "vkFlushMappedMemoryRanges");
}

void StagingArea::invalidate_for_host_reads() const {
  if (coherent) return;
  VkMappedMemoryRange r{VK_STRUCTURE_TYPE_MAPPED_MEMORY_RANGE, nullptr, memory_, 0, VK_WHOLE_SIZE};
  check(vkInvalidateMappedMemoryRanges(ctx_.device, 1, &r), "vkInvalidateMappedMemoryRanges");
}

size_t staging_bytes_for(size_t largest) {
  // Powers of two from 1 MiB, so a growing series of transfers reallocates rarely.
  size_t bytes = size_t(1) << 20;
  while (bytes < largest && bytes < kStagingMaxBytes) bytes *= 2;
  return bytes;
}

StagingArea& staging_area(Context& ctx, size_t bytes) {
  const size_t want = staging_bytes_for(bytes);
  // After a timed-out submission the area may still be in use by it: take a new one (the
  // old one is destroyed with the abandoned work, see Context::~Context).
  if (!ctx.staging || ctx.staging->size < want || ctx.has_abandoned_work()) {
    ctx.staging.reset();
    ctx.staging = std::make_unique<StagingArea>(ctx, want);
  }
  return *ctx.staging;
}

// Host writes -> transfer reads (already implied by the submission after a flush; stated
// so the copy's dependency is visible in the command buffer).
static void host_to_transfer(VkCommandBuffer cmd) {
  VkMemoryBarrier b{VK_STRUCTURE_TYPE_MEMORY_BARRIER, nullptr, VK_ACCESS_HOST_WRITE_BIT,
                    VK_ACCESS_TRANSFER_READ_BIT};
  vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_HOST_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 1, &b,
                       0, nullptr, 0, nullptr);
}

FillBytes copy_from(const void* data, unsigned threads) {
  return [data, threads](char* to, size_t first, size_t n) {
    const char* from = static_cast<const char*>(data) + first;
    // Several cores: one thread's copy into uncached, write-combined memory is well below
    // the bus's rate.
    parallel_for(n, threads, size_t(4) << 20, [&](size_t begin, size_t end) {
      std::memcpy(to + begin, from + begin, end - begin);
    });
  };
}

void staged_upload(Context& ctx, VkBuffer dst, size_t offset, size_t bytes, const FillBytes& fill) {
  StagingArea& s = staging_area(ctx, bytes);
  // Areas are powers of two from 1 MiB: a half is a multiple of 256 KiB (the limit, a
  // power of two from 64 KiB, keeps chunks multiples of 32 bytes too).
  size_t chunk = bytes > s.size ? s.size / 2 : s.size;
  if (ctx.staging_chunk_limit) chunk = std::min(chunk, ctx.staging_chunk_limit);
  PendingSubmission copies[2];
  size_t k = 0;
  for (size_t done = 0; done < bytes; done += chunk, ++k) {
    const size_t n = std::min(chunk, bytes - done), half = k % 2;
    copies[half].wait();  // its previous copy has read the half out
    fill(s.mapped + half * chunk, done, n);
    s.flush_host_writes(half * chunk, n);
    // The submission ends with the barrier that makes the copy visible to later shaders.
    copies[half] = PendingSubmission(ctx, "upload", [&](VkCommandBuffer cmd) {
      host_to_transfer(cmd);
      VkBufferCopy c{half * chunk, offset + done, n};
      vkCmdCopyBuffer(cmd, s.buffer, dst, 1, &c);
    });
    ++ctx.staged_copies;
  }
  copies[k % 2].wait();  // the older one first: copies complete in submission order
  copies[(k + 1) % 2].wait();
}

void staged_download(Context& ctx, VkBuffer src, size_t offset, void* data, size_t bytes) {
  StagingArea& s = staging_area(ctx, bytes);
  for (size_t done = 0; done < bytes; done += s.size) {
    const size_t n = std::min(s.size, bytes - done);
    // The earlier submissions' closing barriers made the shader writes visible to this
    // copy; this one's makes the copy visible to the host (submit()).
    submit(ctx, "download", [&](VkCommandBuffer cmd) {
      VkBufferCopy c{offset + done, 0, n};
      vkCmdCopyBuffer(cmd, src, s.buffer, 1, &c);
    });
    ++ctx.staged_copies;
    s.invalidate_for_host_reads();
    std::memcpy(static_cast<char*>(data) + done, s.mapped, n);
  }
}

}  // namespace meshsal::vk

namespace meshsal::vk {

void RecordedDownload::record(Context& ctx, VkCommandBuffer cmd, const Buffer& src,
                              size_t offset, size_t bytes, size_t at) {
  if (offset + bytes > src.size() || at + bytes > kStagingMaxBytes)
    throw Error("internal: a recorded download past its buffer or the staging area");
  src_ = &src;
  offset_ = offset;
  bytes_ = bytes;
  at_ = at;
  area_ = nullptr;
  if (src.mapped() || bytes == 0) return;
  // Growing the area here would free one an earlier record() of this command buffer uses.
  if (!ctx.staging || ctx.staging->size < at + bytes)
    throw Error("internal: reserve the staging area (staging_area) before recording downloads");
  area_ = ctx.staging.get();
  barrier(cmd);  // the shader writes before it -> this copy
  VkBufferCopy c{offset, at, bytes};
  vkCmdCopyBuffer(cmd, src.handle(), area_->buffer, 1, &c);
  ++ctx.staged_copies;
  // submit() closes the command buffer with the barrier to the host.
}

void RecordedDownload::finish(void* data) {
  if (!src_ || bytes_ == 0) return;
  if (!area_) {
    src_->download(data, bytes_, offset_);  // mapped: a memcpy
    return;
  }
  area_->invalidate_for_host_reads();
  std::memcpy(data, area_->mapped + at_, bytes_);
}

}  // namespace meshsal::vk
