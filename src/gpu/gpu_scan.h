// meshsal: the exclusive prefix sum on the device that the grid build, the radix sort's
// digits and the fast method's runs share (scan_blocks.comp): blocks of 4096 entries summed
// by one work group each, the block sums scanned, each block scanned and offset, so that
// every work group is busy however long the array (the digit counts are as many as the
// keys). CPU twin: std::exclusive_scan (tests/gpu/test_gpu_scan.cpp).
#pragma once
#include <cstdint>

#include "gpu/vk_buffer.h"
#include "gpu/vk_compute.h"

namespace meshsal::gpu {

class Scan {
 public:
  // Scans of `in` into `out` (max_n + 1 entries) of up to max_n entries.
  Scan(vk::Context& ctx, vk::DescriptorPool& pool, const vk::Buffer& in, vk::Buffer& out, uint32_t max_n);
  // Its descriptor sets name its own buffers: neither copied nor moved.
  Scan(const Scan&) = delete;
  Scan& operator=(const Scan&) = delete;
  // out[i] = in[0] + ... + in[i-1] for i <= n (n <= max_n). Ends with a barrier.
  void record(vk::Context& ctx, VkCommandBuffer cmd, uint32_t n) const;
  static constexpr uint32_t kSets = 1, kBuffers = 3;  // what it takes from the pool
  static uint64_t bytes(uint64_t max_n) { return (max_n / 4096 + 2) * 4; }

 private:
  uint32_t max_n_;
  const vk::Buffer* out_;
  vk::Buffer block_;
  const vk::Kernel* k_;
  VkDescriptorSet set_;
};

}  // namespace meshsal::gpu
