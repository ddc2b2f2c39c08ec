// meshsal: the GPU grid build (see gpu_grid.h).
#include "gpu/gpu_grid.h"

#include <algorithm>
#include <cmath>

#include "meshsal/meshsal.h"
#include "core/mesh_points.h"
#include "gpu/vk_compute.h"
#include "saliency/spatial_grid.h"

#include "grid_gather_comp.h"
#include "grid_key_comp.h"
#include "grid_radix_count_comp.h"
#include "grid_radix_scatter_comp.h"
#include "grid_scan_comp.h"

namespace meshsal {

namespace {
constexpr uint32_t kLocal = 64;   // local_size_x of the grid shaders
constexpr uint32_t kTile = 256;   // items per invocation of the radix passes (TILE)
struct KeyPush { uint32_t base, n, nx, ny, nz, pad; double h; };
struct RangePush { uint32_t base, n; };
struct RadixPush { uint32_t base, n, items, shift, first; };

// One work group scans count[0, n) into start[0, n] (start[n] = total).
void scan(VkCommandBuffer cmd, const vk::Kernel& k, VkDescriptorSet set, uint32_t n) {
  RangePush p{0, n};
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, k.pipeline);
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, k.layout, 0, 1, &set, 0, nullptr);
  vkCmdPushConstants(cmd, k.layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof p, &p);
  vkCmdDispatch(cmd, 1, 1, 1);
}

uint32_t radix_passes(uint64_t largest_key) {
  uint32_t bits = 0;
  while (bits < 32 && (largest_key >> bits) != 0) ++bits;
  return std::max<uint32_t>(1, (bits + 7) / 8);
}
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
  const uint64_t tiles = (nv + kTile - 1) / kTile;
  return nv * 16 + (256 * tiles + 1) * 4 + cells * 4;
}

GridPlan build_gpu_grid(vk::Context& ctx, const GridArrays& a, uint32_t nv, uint32_t np,
                        const double extent[3], double cell, std::vector<uint32_t>* starts_out) {
  GridPlan g = plan_grid(extent, cell, np, ctx.properties.limits.maxStorageBufferRange / 4 - 1);
  const uint32_t cells = static_cast<uint32_t>(g.cells());
  const uint32_t tiles = (nv + kTile - 1) / kTile;
  const uint32_t digits = 256 * tiles;
  vk::Buffer cell_count(ctx, size_t(cells) * 4, "the grid cell counts");
  *a.starts = vk::Buffer(ctx, size_t(cells + 1) * 4, "the grid cell starts");
  vk::Buffer key[2] = {vk::Buffer(ctx, size_t(nv) * 4, "the cell keys"),
                       vk::Buffer(ctx, size_t(nv) * 4, "the sorted cell keys")};
  vk::Buffer value[2] = {vk::Buffer(ctx, size_t(nv) * 4, "the sorted vertices"),
                         vk::Buffer(ctx, size_t(nv) * 4, "the sorted vertices")};
  vk::Buffer counts(ctx, size_t(digits) * 4, "the radix digit counts");
  vk::Buffer offsets(ctx, size_t(digits + 1) * 4, "the radix digit offsets");

  const std::vector<int32_t> tile{int32_t(kTile)};
  auto& k_key = vk::cached_kernel(ctx, spv_grid_key_comp, sizeof spv_grid_key_comp, 4,
                                  sizeof(KeyPush), "grid_key");
  auto& k_scan = vk::cached_kernel(ctx, spv_grid_scan_comp, sizeof spv_grid_scan_comp, 2,
                                   sizeof(RangePush), "grid_scan");
  auto& k_count = vk::cached_kernel(ctx, spv_grid_radix_count_comp, sizeof spv_grid_radix_count_comp,
                                    2, sizeof(RadixPush), "grid_radix_count", tile);
  auto& k_scatter = vk::cached_kernel(ctx, spv_grid_radix_scatter_comp,
                                      sizeof spv_grid_radix_scatter_comp, 5, sizeof(RadixPush),
                                      "grid_radix_scatter", tile);
  auto& k_gather = vk::cached_kernel(ctx, spv_grid_gather_comp, sizeof spv_grid_gather_comp, 4,
                                     sizeof(RangePush), "grid_gather");
  vk::DescriptorPool pool(ctx, 8, 32);
  VkDescriptorSet s_key = pool.bind(k_key, {a.pos, a.flags, &cell_count, &key[0]});
  VkDescriptorSet s_scan = pool.bind(k_scan, {&cell_count, a.starts});
  VkDescriptorSet s_digits = pool.bind(k_scan, {&counts, &offsets});
  VkDescriptorSet s_count[2], s_scatter[2];
  for (int i = 0; i < 2; ++i) {  // pass p reads array p % 2 and writes the other
    s_count[i] = pool.bind(k_count, {&key[i], &counts});
    s_scatter[i] = pool.bind(k_scatter, {&key[i], &value[i], &offsets, &key[1 - i], &value[1 - i]});
  }
  const uint32_t passes = radix_passes(cells);  // keys run up to `cells` (not a point)
  vk::Buffer& order = value[passes % 2];
  VkDescriptorSet s_gather = pool.bind(k_gather, {a.pos, &order, a.sorted_pos, a.sorted_vertex});

  vk::submit(ctx, "grid", [&](VkCommandBuffer cmd) {
    vkCmdFillBuffer(cmd, cell_count.handle(), 0, VK_WHOLE_SIZE, 0);
    vk::barrier(cmd);
    KeyPush kp{0, 0, g.nx, g.ny, g.nz, 0, g.h};
    vk::dispatch(ctx, cmd, k_key, s_key, &kp, 0, nv, kLocal);
    vk::barrier(cmd);
    scan(cmd, k_scan, s_scan, cells);
    for (uint32_t p = 0; p < passes; ++p) {
      RadixPush rp{0, 0, nv, 8 * p, p == 0};
      vk::dispatch(ctx, cmd, k_count, s_count[p % 2], &rp, 0, tiles, kLocal);
      vk::barrier(cmd);
      scan(cmd, k_scan, s_digits, digits);
      vk::barrier(cmd);
      vk::dispatch(ctx, cmd, k_scatter, s_scatter[p % 2], &rp, 0, tiles, kLocal);
      vk::barrier(cmd);
    }
    RangePush gp{0, 0};
    vk::dispatch(ctx, cmd, k_gather, s_gather, &gp, 0, np, kLocal);
  });
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
