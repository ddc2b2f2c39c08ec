// meshsal: the shared GPU radix sort (gpu_radix_sort.h).
#include "gpu/gpu_radix_sort.h"

#include <algorithm>
#include <vector>

#include "grid_radix_count_comp.h"
#include "grid_radix_scatter_comp.h"
#include "grid_scan_comp.h"
#include "gpu/shader_interfaces.h"

namespace meshsal::gpu {

namespace {
constexpr uint32_t kLocal = 64;       // local_size_x of the radix shaders
constexpr uint32_t kRadixTile = 256;  // keys per invocation of the count and scatter passes
using shader::RadixPush;  // the push blocks: gpu/shader_interfaces.h
using shader::RangePush;

uint32_t radix_passes(uint64_t largest_key) {
  uint32_t bits = 0;
  while (bits < 32 && (largest_key >> bits) != 0) ++bits;
  return std::max<uint32_t>(1, (bits + 7) / 8);
}
}  // namespace

vk::Kernel& scan_kernel(vk::Context& ctx) {
  return vk::cached_kernel<shader::GridScan>(ctx, spv_grid_scan_comp, sizeof spv_grid_scan_comp, "grid_scan");
}

void record_scan(VkCommandBuffer cmd, const vk::Kernel& k, VkDescriptorSet set, uint32_t n) {
  RangePush p{0, n};
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, k.pipeline);
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, k.layout, 0, 1, &set, 0, nullptr);
  vkCmdPushConstants(cmd, k.layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof p, &p);
  vkCmdDispatch(cmd, 1, 1, 1);
}

uint64_t RadixSort::bytes(uint64_t n) {
  const uint64_t tiles = (n + kRadixTile - 1) / kRadixTile;
  return n * 16 + (2 * 256 * tiles + 1) * 4;  // keys and values twice, digit counts and offsets
}

RadixSort::RadixSort(vk::Context& ctx, vk::DescriptorPool& pool, uint32_t n, uint64_t largest_key,
                     const std::string& what)
    : n_(n), tiles_((n + kRadixTile - 1) / kRadixTile), digits_(256 * tiles_), passes_(radix_passes(largest_key)) {
  key_[0] = vk::Buffer(ctx, size_t(n) * 4, what + " cell keys");
  key_[1] = vk::Buffer(ctx, size_t(n) * 4, what + " sorted cell keys");
  value_[0] = vk::Buffer(ctx, size_t(n) * 4, what + " sorted vertices");
  value_[1] = vk::Buffer(ctx, size_t(n) * 4, what + " sorted vertices");
  counts_ = vk::Buffer(ctx, size_t(digits_) * 4, "the radix digit counts");
  offsets_ = vk::Buffer(ctx, size_t(digits_ + 1) * 4, "the radix digit offsets");
  const std::vector<int32_t> tile{int32_t(kRadixTile)};
  count_ = &vk::cached_kernel<shader::GridRadixCount>(ctx, spv_grid_radix_count_comp, sizeof spv_grid_radix_count_comp, "grid_radix_count", tile);
  scatter_ = &vk::cached_kernel<shader::GridRadixScatter>(ctx, spv_grid_radix_scatter_comp, sizeof spv_grid_radix_scatter_comp, "grid_radix_scatter", tile);
  scan_ = &scan_kernel(ctx);
  s_digits_ = pool.bind(*scan_, {&counts_, &offsets_});
  for (int i = 0; i < 2; ++i) {  // pass p reads array p % 2 and writes the other
    s_count_[i] = pool.bind(*count_, {&key_[i], &counts_});
    s_scatter_[i] = pool.bind(*scatter_, {&key_[i], &value_[i], &offsets_, &key_[1 - i], &value_[1 - i]});
  }
}

void RadixSort::record(vk::Context& ctx, VkCommandBuffer cmd) const {
  for (uint32_t p = 0; p < passes_; ++p) {
    RadixPush rp{0, 0, n_, 8 * p, p == 0};
    vk::dispatch(ctx, cmd, *count_, s_count_[p % 2], &rp, 0, tiles_, kLocal);
    vk::barrier(cmd);
    record_scan(cmd, *scan_, s_digits_, digits_);
    vk::barrier(cmd);
    vk::dispatch(ctx, cmd, *scatter_, s_scatter_[p % 2], &rp, 0, tiles_, kLocal);
    vk::barrier(cmd);
  }
}

}  // namespace meshsal::gpu
