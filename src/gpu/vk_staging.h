// meshsal: the staging area of the discrete-GPU memory path. Device buffers there live in
// device-local memory the host does not map; every upload and download is copied through
// one host-visible buffer (host-cached where the device has it, for fast read-back) that
// the Context keeps and reuses, in chunks of at most its size.
#pragma once
#include <cstddef>
#include <cstdint>
#include <functional>

#include "gpu/vk_context.h"

namespace meshsal::vk {

// Largest staging area: longer transfers go through it in chunks of this size.
constexpr size_t kStagingMaxBytes = size_t(64) << 20;

class Buffer;  // vk_buffer.h

class StagingArea {
 public:
  StagingArea(Context& ctx, size_t bytes);
  ~StagingArea();
  StagingArea(const StagingArea&) = delete;
  StagingArea& operator=(const StagingArea&) = delete;

  VkBuffer buffer = VK_NULL_HANDLE;
  size_t size = 0;
  char* mapped = nullptr;
  bool coherent = false;  // else host writes are flushed and reads invalidated by hand

  void flush_host_writes() const;        // host writes -> visible to the device's copies
  // The same for the bytes [offset, offset + bytes) alone (rounded out to the device's
  // nonCoherentAtomSize): the other half of the area may be in a copy meanwhile.
  void flush_host_writes(size_t offset, size_t bytes) const;
  void invalidate_for_host_reads() const;  // device writes (made available) -> host reads

 private:
  Context& ctx_;
  VkDeviceMemory memory_ = VK_NULL_HANDLE;
};

// Staging bytes the context will allocate for transfers of up to `largest` bytes.
size_t staging_bytes_for(size_t largest);

// Writes bytes [first, first + n) of a transfer at `to` (host memory the device reads: a
// staging chunk, or a mapped buffer). It may run on several threads itself.
using FillBytes = std::function<void(char* to, size_t first, size_t n)>;

// Fills dst[offset, offset + bytes) through ctx.staging (made or grown on first use), in
// chunks of half the area when it takes more than one: the host fills one half while the
// device copies the other (one fenced submission per chunk, waited for before its half is
// refilled). Chunks start at multiples of 64 KiB of the transfer (of 256 KiB but under
// Context::staging_chunk_limit).
void staged_upload(Context& ctx, VkBuffer dst, size_t offset, size_t bytes, const FillBytes& fill);
// dst's range out to the host through ctx.staging; one fenced submission per chunk.
void staged_download(Context& ctx, VkBuffer src, size_t offset, void* data, size_t bytes);

// A FillBytes that copies from `data` (offsets relative to it), on `threads` threads (0:
// the process's share of the cores).
FillBytes copy_from(const void* data, unsigned threads = 0);

// The context's staging area, made or grown to hold min(bytes, kStagingMaxBytes).
StagingArea& staging_area(Context& ctx, size_t bytes);

// A download recorded into a command buffer of the caller's own submission (no submission
// of its own): record() copies src[offset, offset + bytes) into the staging area at
// `at` (several downloads in one submission need disjoint places, and the area must be
// reserved for all of them with staging_area() before recording); after that
// submission's fence, finish() copies it out. Where src is mapped, record() does nothing
// and finish() reads the mapping.
struct RecordedDownload {
  void record(Context& ctx, VkCommandBuffer cmd, const Buffer& src, size_t offset,
              size_t bytes, size_t at = 0);
  void finish(void* data);

 private:
  const Buffer* src_ = nullptr;
  StagingArea* area_ = nullptr;
  size_t offset_ = 0, bytes_ = 0, at_ = 0;
};

}  // namespace meshsal::vk
