// meshsal: the GPU grid build (see gpu_grid.h).
#include "gpu/gpu_grid.h"

#include <algorithm>
#include <cmath>

#include "meshsal/meshsal.h"
#include "core/mesh_points.h"
#include "gpu/gpu_radix_sort.h"
#include "gpu/shader_interfaces.h"
#include "gpu/vk_compute.h"
#include "saliency/spatial_grid.h"

#include "grid_gather_comp.h"
#include "grid_key_comp.h"

namespace meshsal {

namespace {
constexpr uint32_t kLocal = 64;   // local_size_x of the grid shaders
using gpu::shader::GridKeyPush;  // the push blocks: gpu/shader_interfaces.h
using gpu::shader::RangePush;
}  // namespace

GridPlan plan_grid(const double extent[3], double min_cell, uint64_t points, uint64_t limit) {
  GridPlan g;
  const double cell = grid_cell_size(extent, min_cell, points, double(limit));
  g.h = cell;
  g.nx = uint32_t(std::floor(extent[0] / cell)) + 1;
  g.ny = uint32_t(std::floor(extent[1] / cell)) + 1;
  g.nz = uint32_t(std::floor(extent[2] / cell)) + 1;
  return g;
}

uint64_t gpu_grid_scratch_bytes(uint64_t nv, uint64_t cells) {
  return gpu::RadixSort::bytes(nv) + cells * 4 + gpu::Scan::bytes(cells);
}

// The cell starts (max_cells + 1), made where the caller keeps them.
vk::Buffer& made(vk::Context& ctx, vk::Buffer* starts, uint64_t max_cells) {
  *starts = vk::Buffer(ctx, size_t(max_cells + 1) * 4, "the grid cell starts");
  return *starts;
}

GridBuilder::GridBuilder(vk::Context& ctx, vk::DescriptorPool& pool, const GridArrays& a, uint32_t n,
                         uint64_t max_cells)
    : n_(n), cell_count_(ctx, size_t(max_cells) * 4, "the grid cell counts"),
      sort_(ctx, pool, n, max_cells, "the grid's"),  // keys run up to the cells (not a point)
      scan_(ctx, pool, cell_count_, made(ctx, a.starts, max_cells), uint32_t(max_cells)) {
  k_key_ = &vk::cached_kernel<gpu::shader::GridKey>(ctx, spv_grid_key_comp, sizeof spv_grid_key_comp, "grid_key");
  k_gather_ = &vk::cached_kernel<gpu::shader::GridGather>(ctx, spv_grid_gather_comp, sizeof spv_grid_gather_comp, "grid_gather");
  s_key_ = pool.bind(*k_key_, {a.pos, a.flags, &cell_count_, &sort_.keys_in()});
  s_gather_ = pool.bind(*k_gather_, {a.pos, &sort_.order(), a.sorted_pos, a.sorted_vertex});
}

void GridBuilder::record(vk::Context& ctx, VkCommandBuffer cmd, const GridPlan& g, uint32_t gather) {
  const uint32_t cells = static_cast<uint32_t>(g.cells());
  vkCmdFillBuffer(cmd, cell_count_.handle(), 0, VkDeviceSize(cells) * 4, 0);
  vk::barrier(cmd);
  GridKeyPush kp{0, 0, g.nx, g.ny, g.nz, 0, g.h};
  vk::dispatch(ctx, cmd, *k_key_, s_key_, &kp, 0, n_, kLocal);
  vk::barrier(cmd);
  scan_.record(ctx, cmd, cells);
  sort_.record(ctx, cmd);
  RangePush gp{0, 0};
  vk::dispatch(ctx, cmd, *k_gather_, s_gather_, &gp, 0, gather, kLocal);
  vk::barrier(cmd);
}

GridPlan build_gpu_grid(vk::Context& ctx, const GridArrays& a, uint32_t nv, uint32_t np,
                        const double extent[3], double cell, std::vector<uint32_t>* starts_out) {
  GridPlan g = plan_grid(extent, cell, np, ctx.properties.limits.maxStorageBufferRange / 4 - 1);
  const uint32_t cells = static_cast<uint32_t>(g.cells());
  vk::DescriptorPool pool(ctx, GridBuilder::kSets, GridBuilder::kBuffers);
  GridBuilder build(ctx, pool, a, nv, cells);
  vk::submit(ctx, "grid", [&](VkCommandBuffer cmd) { build.record(ctx, cmd, g, np); });
  starts_out->resize(size_t(cells) + 1);
  a.starts->download(starts_out->data(), starts_out->size() * 4);
  if ((*starts_out)[cells] != np)
    throw Error("internal: the GPU grid holds " + std::to_string((*starts_out)[cells]) +
                " points instead of " + std::to_string(np));
  return g;
}

void gpu_grid_order(vk::Context& ctx, const Mesh& mesh, const std::vector<uint8_t>& is_point,
                    double cell, std::vector<uint32_t>* order, std::vector<uint32_t>* starts) {
  const size_t nv = mesh.vertex_count();
  BoundingBox bb = mesh_points_bbox(mesh, is_point);
  double extent[3];
  for (int a = 0; a < 3; ++a) extent[a] = bb.max[a] - bb.min[a];
  std::vector<double> pos4(4 * nv, 0.0);
  std::vector<uint32_t> flags(nv);
  uint32_t np = 0;
  for (size_t v = 0; v < nv; ++v) {
    for (int a = 0; a < 3; ++a) pos4[4 * v + a] = double(mesh.positions[3 * v + a]) - bb.min[a];
    flags[v] = is_point[v];
    np += is_point[v];
  }
  vk::Buffer pos(ctx, nv * 32, "the vertex positions"), fl(ctx, nv * 4, "the mesh-point flags");
  vk::Buffer st, sorted_pos(ctx, size_t(np) * 32, "the sorted points"),
      sorted_vertex(ctx, size_t(np) * 4, "the sorted point indices");
  pos.upload(pos4.data(), pos4.size() * 8);
  fl.upload(flags.data(), flags.size() * 4);
  build_gpu_grid(ctx, {&pos, &fl, &st, &sorted_pos, &sorted_vertex}, uint32_t(nv), np, extent,
                 cell, starts);
  order->resize(np);
  sorted_vertex.download(order->data(), size_t(np) * 4);
}

}  // namespace meshsal
