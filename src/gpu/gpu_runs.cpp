// meshsal: the runs of a sorted key array on the device (gpu_runs.h).
#include "gpu/gpu_runs.h"

#include "gpu/shader_interfaces.h"

#include "run_heads_comp.h"
#include "run_starts_comp.h"

namespace meshsal::gpu {

namespace {
constexpr uint32_t kLocal = 64;  // local_size_x of the shaders
using shader::RunPush;
}  // namespace

RunFinder::RunFinder(vk::Context& ctx, vk::DescriptorPool& pool, const RunArrays& a, uint32_t max_n)
    : scan_(ctx, pool, *a.head, *a.scan, max_n),
      heads_(&vk::cached_kernel<shader::RunHeads>(ctx, spv_run_heads_comp, sizeof spv_run_heads_comp, "run_heads")),
      starts_(&vk::cached_kernel<shader::RunStarts>(ctx, spv_run_starts_comp, sizeof spv_run_starts_comp, "run_starts")) {
  s_heads_ = pool.bind(*heads_, {a.keys, a.counts, a.head});
  // Buffers a use does not write are bound to ones it has (never touched: the flags say so).
  s_starts_ = pool.bind(*starts_, {a.keys, a.scan, a.counts, a.run_first, a.run_key ? a.run_key : a.head,
                                   a.value ? a.value : a.keys, a.item_run ? a.item_run : a.head});
}

void RunFinder::record(vk::Context& ctx, VkCommandBuffer cmd, uint32_t n, uint32_t count_slot,
                       uint32_t total_slot, uint32_t flags) const {
  RunPush p{0, 0, count_slot, total_slot, flags};
  vk::dispatch(ctx, cmd, *heads_, s_heads_, &p, 0, n, kLocal);
  vk::barrier(cmd);
  scan_.record(ctx, cmd, n);
  vk::dispatch(ctx, cmd, *starts_, s_starts_, &p, 0, n, kLocal);
  vk::barrier(cmd);
}

}  // namespace meshsal::gpu
