// meshsal: the GPU radix sort of vertices by 32-bit keys that the grid build (gpu_grid.cpp)
// and the fast method's cell sort (gpu_fast_cells.cpp) share: 8 bits a pass, each pass a
// count per tile, one scan of the digit counts and a stable scatter (grid_radix_count.comp,
// gpu_scan.h, grid_radix_scatter.comp); the first pass writes the vertex ids as values.
// The CPU twin is the counting sort of the cells in saliency/spatial_grid.cpp.
#pragma once
#include <cstdint>
#include <string>

#include "gpu/gpu_scan.h"
#include "gpu/vk_compute.h"

namespace meshsal::gpu {

class RadixSort {
 public:
  // Room for `n` keys up to `largest_key` (which sets the passes: a sort made once for
  // several key ranges takes the largest); buffer names start with `what` ("the grid's").
  // The caller fills keys_in() on the device, then records record() after a barrier.
  RadixSort(vk::Context& ctx, vk::DescriptorPool& pool, uint32_t n, uint64_t largest_key,
            const std::string& what);
  // Its descriptor sets name its own buffers: neither copied nor moved.
  RadixSort(const RadixSort&) = delete;
  RadixSort& operator=(const RadixSort&) = delete;
  vk::Buffer& keys_in() { return key_[0]; }
  // The passes, each followed by a barrier.
  void record(vk::Context& ctx, VkCommandBuffer cmd) const;
  vk::Buffer& sorted_keys() { return key_[passes_ % 2]; }
  vk::Buffer& order() { return value_[passes_ % 2]; }  // vertex ids in key order
  static constexpr uint32_t kSets = 4 + Scan::kSets, kBuffers = 14 + Scan::kBuffers;  // what the constructor takes from the pool
  // Device bytes the sort of n keys holds (keys, values, digit counts and offsets).
  static uint64_t bytes(uint64_t n);

 private:
  uint32_t n_ = 0, tiles_ = 0, digits_ = 0, passes_ = 0;
  vk::Buffer key_[2], value_[2], counts_, offsets_;
  Scan scan_;
  const vk::Kernel* count_ = nullptr;
  const vk::Kernel* scatter_ = nullptr;
  VkDescriptorSet s_count_[2] = {}, s_scatter_[2] = {};
};

}  // namespace meshsal::gpu
