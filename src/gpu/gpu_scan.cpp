// meshsal: the device prefix sum (gpu_scan.h).
#include "gpu/gpu_scan.h"

#include "meshsal/meshsal.h"
#include "gpu/shader_interfaces.h"

#include "scan_blocks_comp.h"

namespace meshsal::gpu {

namespace {
constexpr uint32_t kBlock = 4096;  // entries per work group (256 threads x 16: scan_blocks.comp)
}  // namespace

Scan::Scan(vk::Context& ctx, vk::DescriptorPool& pool, const vk::Buffer& in, vk::Buffer& out, uint32_t max_n)
    : max_n_(max_n), out_(&out), block_(ctx, size_t(max_n / kBlock + 2) * 4, "the prefix sum's blocks"),
      k_(&vk::cached_kernel<shader::ScanBlocks>(ctx, spv_scan_blocks_comp, sizeof spv_scan_blocks_comp, "scan_blocks")) {
  set_ = pool.bind(*k_, {&in, &out, &block_});
}

void Scan::record(vk::Context& ctx, VkCommandBuffer cmd, uint32_t n) const {
  if (n > max_n_) throw Error("internal: a prefix sum of " + std::to_string(n) + " entries, room for " +
                              std::to_string(max_n_));
  if (n == 0) {
    vkCmdFillBuffer(cmd, out_->handle(), 0, 4, 0);
    vk::barrier(cmd);
    return;
  }
  const uint32_t blocks = (n + kBlock - 1) / kBlock;
  shader::ScanPush p{0, 0, n, 0};
  // vk::dispatch sets {base, nblocks}; a "local size" of 1 makes it a work group per block.
  vk::dispatch(ctx, cmd, *k_, set_, &p, 0, blocks, 1);
  vk::barrier(cmd);
  // One work group over the block sums (pipeline and set still bound).
  shader::ScanPush one{0, blocks, n, 1};
  vkCmdPushConstants(cmd, k_->layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof one, &one);
  vkCmdDispatch(cmd, 1, 1, 1);
  vk::barrier(cmd);
  p.mode = 2;
  vk::dispatch(ctx, cmd, *k_, set_, &p, 0, blocks, 1);
  vk::barrier(cmd);
}

}  // namespace meshsal::gpu
