// meshsal: --method fast, the query groups on the device (gpu_fast_groups.h).
#include "gpu/gpu_fast_groups.h"

#include "meshsal/meshsal.h"
#include "gpu/shader_interfaces.h"

#include "fast_group_centroids_comp.h"
#include "fast_group_key_comp.h"

namespace meshsal::gpu {

namespace {
constexpr uint32_t kLocal = 64;  // local_size_x of the shaders
using shader::CountedPush;
using shader::GroupKeyPush;

}  // namespace

uint64_t fast_groups_bytes(uint64_t np) {
  // the sort, heads and scan, group starts, each cell's group, the centroids
  return RadixSort::bytes(np) + np * 8 + np * 4 + np * 4 + np * 32 + 16 + Scan::bytes(np);
}

FastGroups::FastGroups(vk::Context& ctx, vk::DescriptorPool& pool, FastCells& cells, vk::Buffer& counts,
                       uint64_t most_cells, int factor)
    : group_start(ctx, size_t(cells.np() + 1) * 4, "the fast method's query groups"),
      cell_group(ctx, size_t(cells.np()) * 4, "the fast method's query groups"),
      group_pos(ctx, size_t(cells.np()) * 32, "the query groups' centroids"),
      np_(cells.np()), factor_(factor),
      // a coarse key never exceeds the fine cells' count
      sort_(ctx, pool, cells.np(), most_cells, "the query groups'"),
      head_(ctx, size_t(cells.np()) * 4, "the query groups' run heads"),
      scan_(ctx, size_t(cells.np() + 1) * 4, "the query groups' run scan"),
      runs_(ctx, pool, {&sort_.sorted_keys(), &counts, &head_, &scan_, &group_start, nullptr, &sort_.order(),
                        &cell_group}, cells.np()) {
  if (factor < 1) throw Error("internal: query groups need a factor of at least 1");
  k_key_ = &vk::cached_kernel<shader::FastGroupKey>(ctx, spv_fast_group_key_comp, sizeof spv_fast_group_key_comp, "fast_group_key");
  k_centroids_ = &vk::cached_kernel<shader::FastGroupCentroids>(ctx, spv_fast_group_centroids_comp, sizeof spv_fast_group_centroids_comp, "fast_group_centroids");
  s_key_ = pool.bind(*k_key_, {&cells.cell_key, &counts, &sort_.keys_in()});
  s_centroids_ = pool.bind(*k_centroids_, {&cells.cell_pos, &cells.cell_count, &group_start,
                                           &sort_.order(), &group_pos, &counts});
}

void FastGroups::record(vk::Context& ctx, VkCommandBuffer cmd, const FastGrid& g) {
  const uint32_t f = uint32_t(factor_);
  GroupKeyPush kp{0, 0, kCountCells, f, g.nx, g.ny, uint32_t((g.nx + f - 1) / f),
                  uint32_t((g.ny + f - 1) / f), uint32_t((g.nz + f - 1) / f)};
  vk::dispatch(ctx, cmd, *k_key_, s_key_, &kp, 0, np_, kLocal);
  vk::barrier(cmd);
  sort_.record(ctx, cmd);
  runs_.record(ctx, cmd, np_, kCountCells, kCountGroups, kItemRuns);
  CountedPush cp{0, 0, kCountGroups};
  vk::dispatch(ctx, cmd, *k_centroids_, s_centroids_, &cp, 0, np_, kLocal);
  vk::barrier(cmd);
}

}  // namespace meshsal::gpu
