// meshsal: see gpu_sweep.h.
#include "gpu/gpu_sweep.h"

#include <algorithm>
#include <string>

#include "meshsal/meshsal.h"

#include "near_tie_comp.h"
#include "near_tie_faces_comp.h"
#include "sorted_float_comp.h"
#include "sweep8_list_comp.h"

namespace meshsal::gpu {

uint32_t test_sweep_gap_at = UINT32_MAX;
bool test_skip_recheck = false;

namespace {
constexpr uint32_t kLocal = 64;
// Listed points per recheck submission: each sweeps a whole ball in double, a lane each.
constexpr uint32_t kRecheckPerSubmission = 16384;
}  // namespace

uint64_t total_swept_pairs(const std::vector<uint32_t>& pairs) {
  uint64_t total = 0, missed = 0;
  size_t first = 0;
  for (size_t i = 0; i < pairs.size(); ++i) {
    if (pairs[i] == 0 && missed++ == 0) first = i;
    total += pairs[i];
  }
  if (missed)
    throw Error("internal: the GPU sweep left " + std::to_string(missed) + " of " +
                std::to_string(pairs.size()) + " mesh points unswept (first: sorted point " +
                std::to_string(first) + ", pair count 0)");
  return total;
}

void make_float_points(vk::Context& ctx, vk::DescriptorPool& pool, const vk::Buffer& sorted_pos,
                       vk::Buffer& sorted_pos32, uint32_t np, const double origin[3]) {
  auto& k = vk::cached_kernel<shader::SortedFloat>(ctx, spv_sorted_float_comp, sizeof spv_sorted_float_comp, "sorted_float");
  VkDescriptorSet set = pool.bind(k, {&sorted_pos, &sorted_pos32});
  shader::OriginPush p{0, 0, 0, 0, origin[0], origin[1], origin[2]};
  vk::submit(ctx, "float points", [&](VkCommandBuffer cmd) {
    vk::dispatch(ctx, cmd, k, set, &p, 0, np, kLocal);
  });
}

uint32_t recheck_near_ties(vk::Context& ctx, vk::DescriptorPool& pool, const NearTieBuffers& b,
                           uint32_t nv, uint32_t nmaps, SweepPush push) {
  const bool faces = b.start != nullptr;
  auto& k_mark =
      faces ? vk::cached_kernel<shader::NearTieFaces>(ctx, spv_near_tie_faces_comp, sizeof spv_near_tie_faces_comp,
                                                      "near_tie_faces")
            : vk::cached_kernel<shader::NearTie>(ctx, spv_near_tie_comp, sizeof spv_near_tie_comp, "near_tie");
  vk::Buffer need(ctx, size_t(nv) * 4, "the near-tie marks");
  VkDescriptorSet s_mark =
      faces ? pool.bind(k_mark, {b.raw, b.is_point, b.bound, b.start, b.entry, b.order, b.triangles, &need})
            : pool.bind(k_mark, {b.raw, b.is_point, b.bound, b.offsets, b.neighbors, &need});
  shader::NearTiePush mp{0, 0, nmaps};
  vk::submit(ctx, "near ties", [&](VkCommandBuffer cmd) {
    vk::dispatch(ctx, cmd, k_mark, s_mark, &mp, 0, nv, kLocal);
  });
  std::vector<uint32_t> marks(nv);
  need.download(marks.data(), marks.size() * 4);
  std::vector<uint32_t> list;
  for (uint32_t v = 0; v < nv; ++v)
    if (marks[v]) list.push_back(v);
  if (list.empty() || test_skip_recheck) return static_cast<uint32_t>(list.size());

  vk::Buffer list_buf(ctx, list.size() * 4, "the near-tie points");
  list_buf.upload(list.data(), list.size() * 4);
  auto& k = vk::cached_kernel<shader::Sweep8List>(ctx, spv_sweep8_list_comp, sizeof spv_sweep8_list_comp, "sweep8_list");
  VkDescriptorSet set = pool.bind(k, {b.sorted_pos, b.sorted_vertex, b.starts, b.params, b.raw,
                                      b.pairs, b.pos, &list_buf});
  const uint32_t n = static_cast<uint32_t>(list.size());
  for (uint32_t s = 0; s < n; s += kRecheckPerSubmission) {
    vk::submit(ctx, "near-tie recheck", [&](VkCommandBuffer cmd) {
      vk::dispatch(ctx, cmd, k, set, &push, s, std::min(n, s + kRecheckPerSubmission), kLocal);
    });
  }
  return n;
}

}  // namespace meshsal::gpu
