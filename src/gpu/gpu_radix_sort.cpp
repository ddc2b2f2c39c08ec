// meshsal: the shared GPU radix sort (gpu_radix_sort.h).
#include "gpu/gpu_radix_sort.h"

#include <algorithm>
#include <vector>

#include "grid_radix_count_comp.h"
#include "grid_radix_scatter_comp.h"
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

uint64_t RadixSort::bytes(uint64_t n) {
  const uint64_t tiles = (n + kRadixTile - 1) / kRadixTile;
  // keys and values twice, digit counts and offsets, the scan's blocks
  return n * 16 + (2 * 256 * tiles + 1) * 4 + Scan::bytes(256 * tiles);
}

RadixSort::RadixSort(vk::Context& ctx, vk::DescriptorPool& pool, uint32_t n, uint64_t largest_key,
                     const std::string& what)
    : n_(n), tiles_((n + kRadixTile - 1) / kRadixTile), digits_(256 * tiles_), passes_(radix_passes(largest_key)),
      key_{vk::Buffer(ctx, size_t(n) * 4, what + " cell keys"), vk::Buffer(ctx, size_t(n) * 4, what + " sorted cell keys")},
      value_{vk::Buffer(ctx, size_t(n) * 4, what + " sorted vertices"), vk::Buffer(ctx, size_t(n) * 4, what + " sorted vertices")},
      counts_(ctx, size_t(digits_) * 4, "the radix digit counts"),
      offsets_(ctx, size_t(digits_ + 1) * 4, "the radix digit offsets"),
      scan_(ctx, pool, counts_, offsets_, digits_) {
  const std::vector<int32_t> tile{int32_t(kRadixTile)};
  count_ = &vk::cached_kernel<shader::GridRadixCount>(ctx, spv_grid_radix_count_comp, sizeof spv_grid_radix_count_comp, "grid_radix_count", tile);
  scatter_ = &vk::cached_kernel<shader::GridRadixScatter>(ctx, spv_grid_radix_scatter_comp, sizeof spv_grid_radix_scatter_comp, "grid_radix_scatter", tile);
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
    scan_.record(ctx, cmd, digits_);
    vk::dispatch(ctx, cmd, *scatter_, s_scatter_[p % 2], &rp, 0, tiles_, kLocal);
    vk::barrier(cmd);
  }
}

}  // namespace meshsal::gpu
