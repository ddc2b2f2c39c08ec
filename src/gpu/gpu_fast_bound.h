// meshsal: --method fast, the most candidates any query can walk on the query grid: the
// aggregates in the (2r+1)^3 cells around any cell, r = ceil(radius / h) + 3 (fast_query.comp
// walks the rows of the ball's cells around a box of at most 2 cells in x and 1 in y and z:
// a subset). The host splits each query's candidates into windows of at most
// Context::fast_window_candidates by it. most_candidates() is the host oracle;
// CandidateBound records the same sums on the device (fast_candidate_bound.comp).
#pragma once
#include <cstdint>
#include <vector>

#include "gpu/gpu_grid.h"
#include "gpu/vk_buffer.h"
#include "gpu/vk_compute.h"

namespace meshsal::gpu {

// The window radius in cells of the grid g for a cutoff `radius`.
uint32_t candidate_reach(const GridPlan& g, double radius);

// From the grid's cell starts (cells + 1), by sliding sums along x, y and z.
uint64_t most_candidates(const GridPlan& g, const std::vector<uint32_t>& starts, double radius);

class CandidateBound {
 public:
  // For grids of at most max_cells cells whose starts are in `starts`; the result goes to
  // counts[slot].
  CandidateBound(vk::Context& ctx, vk::DescriptorPool& pool, const vk::Buffer& starts,
                 vk::Buffer& counts, uint64_t max_cells, uint32_t slot);
  // Its descriptor sets name its own buffers: neither copied nor moved.
  CandidateBound(const CandidateBound&) = delete;
  CandidateBound& operator=(const CandidateBound&) = delete;
  // Records the bound for grid g (its starts written before, behind a barrier), ending with
  // a barrier. counts[slot] must be 0 before (the passes take a maximum into it).
  void record(vk::Context& ctx, VkCommandBuffer cmd, const GridPlan& g, double radius) const;
  static constexpr uint32_t kSets = 1, kBuffers = 4;
  static uint64_t bytes(uint64_t max_cells) { return max_cells * 8; }

 private:
  vk::Buffer a_, b_;
  uint32_t slot_;
  const vk::Kernel* k_;
  VkDescriptorSet set_;
};

}  // namespace meshsal::gpu
