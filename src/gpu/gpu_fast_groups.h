// meshsal: --method fast on the device, the query groups of one sigma: the GPU twin of
// group_cells() (saliency/query_groups.h). Each occupied cell's coarse cell of `factor`
// cells per axis (fast_group_key.comp), a stable radix sort of those (the cells of a group
// stay in ascending order), the groups as the runs of the sorted coarse keys (gpu_runs.h),
// each cell's group, and each group's centroid (fast_group_centroids.comp): the queries of
// the dense sums. All on the device; the group count lands in counts[kCountGroups].
#pragma once
#include <cstdint>

#include "gpu/gpu_fast_cells.h"
#include "gpu/gpu_radix_sort.h"
#include "gpu/gpu_runs.h"

namespace meshsal::gpu {

class FastGroups {
 public:
  // For the cells of `cells` (up to its np slots), over fine grids of at most most_cells
  // cells (the finest sigma's: it sets the sort's passes).
  FastGroups(vk::Context& ctx, vk::DescriptorPool& pool, FastCells& cells, vk::Buffer& counts,
             uint64_t most_cells, int factor);
  // Its descriptor sets name its own buffers: neither copied nor moved.
  FastGroups(const FastGroups&) = delete;
  FastGroups& operator=(const FastGroups&) = delete;
  // Records the groups of this sigma's cells (on `grid`) into cmd, ending with a barrier.
  void record(vk::Context& ctx, VkCommandBuffer cmd, const FastGrid& grid);
  static constexpr uint32_t kSets = RadixSort::kSets + RunFinder::kSets + 2;
  static constexpr uint32_t kBuffers = RadixSort::kBuffers + RunFinder::kBuffers + 9;

  // Per group g < counts[kCountGroups]: its cells are group_cell[group_start[g] ..
  // group_start[g+1]) (group_start[groups] = cells); group_pos[g]: the count-weighted
  // centroid of its cells (dvec4, - bbox min). Per cell: cell_group[c], its group.
  vk::Buffer& group_cell() { return sort_.order(); }
  vk::Buffer group_start, cell_group, group_pos;

 private:
  uint32_t np_;
  int factor_;
  RadixSort sort_;
  vk::Buffer head_, scan_;
  RunFinder runs_;
  const vk::Kernel *k_key_, *k_centroids_;
  VkDescriptorSet s_key_, s_centroids_;
};

// Device bytes FastGroups holds for np mesh points.
uint64_t fast_groups_bytes(uint64_t np);

}  // namespace meshsal::gpu
