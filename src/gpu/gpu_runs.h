// meshsal: the runs of equal keys in a sorted array, found on the device (the shared step of
// the fast method's cells and query groups): a head flag per item (run_heads.comp), their
// exclusive scan (gpu_scan.h), and where each run starts (run_starts.comp). The keys'
// count may be one an earlier step of the same submission wrote to the counts buffer, so
// the host never reads it back. Host twins: fast_cell_runs() (gpu_fast_cells.h) and
// close_groups() in saliency/query_groups.cpp.
#pragma once
#include <cstdint>

#include "gpu/gpu_scan.h"
#include "gpu/vk_buffer.h"
#include "gpu/vk_compute.h"

namespace meshsal::gpu {

// The buffers of one use; run_key, value and item_run may be null when not written.
struct RunArrays {
  const vk::Buffer* keys = nullptr;  // sorted, n (a bound) entries
  vk::Buffer* counts = nullptr;      // the counts buffer (uint slots)
  vk::Buffer* head = nullptr;        // scratch, n entries
  vk::Buffer* scan = nullptr;        // n + 1: the runs' numbering (the run of item i: scan[i+1] - 1)
  vk::Buffer* run_first = nullptr;   // runs + 1: each run's first item, then the count
  vk::Buffer* run_key = nullptr;     // runs: each run's key (flag kRunKeys)
  const vk::Buffer* value = nullptr;  // n: where each item came from (flag kItemRuns)
  vk::Buffer* item_run = nullptr;     // item_run[value[i]] = the run of i (flag kItemRuns)
};

constexpr uint32_t kRunKeys = 1, kItemRuns = 2;  // what record() writes besides run_first
constexpr uint32_t kCountIsN = 0xffffffffu;      // count_slot: all n keys count

class RunFinder {
 public:
  // For arrays of up to max_n keys.
  RunFinder(vk::Context& ctx, vk::DescriptorPool& pool, const RunArrays& a, uint32_t max_n);
  // Its descriptor sets name its own buffers: neither copied nor moved.
  RunFinder(const RunFinder&) = delete;
  RunFinder& operator=(const RunFinder&) = delete;
  // The runs among the first counts[count_slot] of the n keys (kCountIsN: n); their number
  // to counts[total_slot]. Ends with a barrier.
  void record(vk::Context& ctx, VkCommandBuffer cmd, uint32_t n, uint32_t count_slot,
              uint32_t total_slot, uint32_t flags) const;
  static constexpr uint32_t kSets = 2 + Scan::kSets, kBuffers = 10 + Scan::kBuffers;  // from the pool

 private:
  Scan scan_;
  const vk::Kernel *heads_, *starts_;
  VkDescriptorSet s_heads_, s_starts_;
};

}  // namespace meshsal::gpu
