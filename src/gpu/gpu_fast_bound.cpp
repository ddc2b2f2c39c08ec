// meshsal: --method fast, the bound on a query's candidates (gpu_fast_bound.h).
#include "gpu/gpu_fast_bound.h"

#include <algorithm>
#include <cmath>

#include "gpu/shader_interfaces.h"

#include "fast_candidate_bound_comp.h"

namespace meshsal::gpu {

namespace {
constexpr uint32_t kLocal = 64;  // local_size_x of the shader
using shader::BoundPush;
}  // namespace

uint32_t candidate_reach(const GridPlan& g, double radius) {
  return uint32_t(std::ceil(radius / g.h)) + 3;
}

uint64_t most_candidates(const GridPlan& g, const std::vector<uint32_t>& starts, double radius) {
  const int64_t r = candidate_reach(g, radius);
  const int64_t nx = g.nx, ny = g.ny, nz = g.nz;
  std::vector<uint32_t> a(size_t(nx * ny * nz)), b(a.size());
  auto at = [&](int64_t x, int64_t y, int64_t z) { return size_t(x + nx * (y + ny * z)); };
  for (int64_t z = 0; z < nz; ++z)
    for (int64_t y = 0; y < ny; ++y) {
      const size_t row = at(0, y, z);
      for (int64_t x = 0; x < nx; ++x)
        a[row + x] = starts[row + std::min(x + r, nx - 1) + 1] - starts[row + std::max<int64_t>(x - r, 0)];
    }
  for (int64_t z = 0; z < nz; ++z)  // along y: a window of 2r+1 rows
    for (int64_t x = 0; x < nx; ++x) {
      uint64_t run = 0;
      for (int64_t y = 0; y < std::min(r, ny); ++y) run += a[at(x, y, z)];
      for (int64_t y = 0; y < ny; ++y) {
        if (y + r < ny) run += a[at(x, y + r, z)];
        b[at(x, y, z)] = uint32_t(run);
        if (y - r >= 0) run -= a[at(x, y - r, z)];
      }
    }
  uint64_t most = 0;
  for (int64_t y = 0; y < ny; ++y)  // along z
    for (int64_t x = 0; x < nx; ++x) {
      uint64_t run = 0;
      for (int64_t z = 0; z < std::min(r, nz); ++z) run += b[at(x, y, z)];
      for (int64_t z = 0; z < nz; ++z) {
        if (z + r < nz) run += b[at(x, y, z + r)];
        most = std::max(most, run);
        if (z - r >= 0) run -= b[at(x, y, z - r)];
      }
    }
  return most;
}

CandidateBound::CandidateBound(vk::Context& ctx, vk::DescriptorPool& pool, const vk::Buffer& starts,
                               vk::Buffer& counts, uint64_t max_cells, uint32_t slot)
    : a_(ctx, size_t(max_cells) * 4, "the fast method's candidate bound"),
      b_(ctx, size_t(max_cells) * 4, "the fast method's candidate bound"),
      slot_(slot),
      k_(&vk::cached_kernel<shader::FastCandidateBound>(ctx, spv_fast_candidate_bound_comp, sizeof spv_fast_candidate_bound_comp, "fast_candidate_bound")) {
  set_ = pool.bind(*k_, {&starts, &a_, &b_, &counts});
}

void CandidateBound::record(vk::Context& ctx, VkCommandBuffer cmd, const GridPlan& g, double radius) const {
  const uint32_t cells = uint32_t(g.cells());
  BoundPush p{0, 0, g.nx, g.ny, g.nz, candidate_reach(g, radius), 0, slot_};
  for (uint32_t mode = 0; mode < 3; ++mode) {
    p.mode = mode;
    vk::dispatch(ctx, cmd, *k_, set_, &p, 0, cells, kLocal);
    vk::barrier(cmd);
  }
}

}  // namespace meshsal::gpu
