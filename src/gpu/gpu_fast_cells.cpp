// meshsal: --method fast, sorting and aggregating the cells on the device (gpu_fast_cells.h).
#include "gpu/gpu_fast_cells.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "meshsal/meshsal.h"
#include "gpu/vk_compute.h"

#include "fast_aggregate_cells_comp.h"
#include "fast_aggregate_pieces_comp.h"
#include "fast_cell_key_comp.h"
#include "grid_radix_count_comp.h"
#include "grid_radix_scatter_comp.h"
#include "grid_scan_comp.h"

namespace meshsal::gpu {

namespace {
constexpr uint32_t kLocal = 64;  // local_size_x of the shaders
constexpr uint32_t kTile = 256;  // items per invocation of the radix passes (as gpu_grid.cpp)
struct KeyPush { uint32_t base, n, nx, ny, nz, pad; double cell; };
struct RangePush { uint32_t base, n; };
struct RadixPush { uint32_t base, n, items, shift, first; };
struct CellsPush { uint32_t base, n, pad0, pad1; double min[3]; };

// One work group scans count[0, n) into start[0, n] (grid_scan.comp).
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

FastGrid plan_fast_grid(const double extent[3], double cell) {
  FastGrid g;
  g.cell = cell;
  uint64_t n[3];
  for (int a = 0; a < 3; ++a) n[a] = uint64_t(extent[a] / cell) + 1;  // as cell_key() floors
  const uint64_t cells = n[0] * n[1] * n[2];
  // The key nx*ny*nz marks a vertex that is not a mesh point: it must fit 32 bits too.
  if (n[0] >= (uint64_t(1) << 32) || n[1] >= (uint64_t(1) << 32) || n[2] >= (uint64_t(1) << 32) ||
      cells >= 0xffffffffull)
    throw Error("the GPU fast method needs fewer than 2^32 cells of sigma/6 over the bounding box "
                "(these scales and eps-frac give " + std::to_string(double(n[0]) * double(n[1]) * double(n[2])) +
                "); use the CPU path (--backend cpu)");
  g.nx = uint32_t(n[0]);
  g.ny = uint32_t(n[1]);
  g.nz = uint32_t(n[2]);
  return g;
}

uint64_t fast_cells_bytes(uint64_t nv, uint64_t np) {
  const uint64_t tiles = (nv + kTile - 1) / kTile;
  const uint64_t sort = nv * 16 + (2 * 256 * tiles + 1) * 4;  // keys, values, digit counts
  const uint64_t pieces = np + np / kFastPiece + 1;           // at most
  return sort + pieces * (4 + 4 + 32) + np * (4 + 32 + 8);    // piece arrays and sums, cells
}

FastCells aggregate_cells(vk::Context& ctx, const FastInputs& in, uint32_t nv, uint32_t np,
                          const FastGrid& g, const double box_min[3]) {
  const uint32_t cells = g.nx * g.ny * g.nz;
  const uint32_t tiles = (nv + kTile - 1) / kTile;
  const uint32_t digits = 256 * tiles;
  vk::Buffer key[2] = {vk::Buffer(ctx, size_t(nv) * 4, "the fast method's cell keys"),
                       vk::Buffer(ctx, size_t(nv) * 4, "the fast method's sorted cell keys")};
  vk::Buffer value[2] = {vk::Buffer(ctx, size_t(nv) * 4, "the fast method's sorted vertices"),
                         vk::Buffer(ctx, size_t(nv) * 4, "the fast method's sorted vertices")};
  vk::Buffer counts(ctx, size_t(digits) * 4, "the radix digit counts");
  vk::Buffer offsets(ctx, size_t(digits + 1) * 4, "the radix digit offsets");

  const std::vector<int32_t> tile{int32_t(kTile)};
  auto& k_key = vk::cached_kernel(ctx, spv_fast_cell_key_comp, sizeof spv_fast_cell_key_comp, 3,
                                  sizeof(KeyPush), "fast_cell_key");
  auto& k_scan = vk::cached_kernel(ctx, spv_grid_scan_comp, sizeof spv_grid_scan_comp, 2,
                                   sizeof(RangePush), "grid_scan");
  auto& k_count = vk::cached_kernel(ctx, spv_grid_radix_count_comp, sizeof spv_grid_radix_count_comp,
                                    2, sizeof(RadixPush), "grid_radix_count", tile);
  auto& k_scatter = vk::cached_kernel(ctx, spv_grid_radix_scatter_comp,
                                      sizeof spv_grid_radix_scatter_comp, 5, sizeof(RadixPush),
                                      "grid_radix_scatter", tile);
  vk::DescriptorPool pool(ctx, 8, 32);
  VkDescriptorSet s_key = pool.bind(k_key, {in.pos, in.flags, &key[0]});
  VkDescriptorSet s_digits = pool.bind(k_scan, {&counts, &offsets});
  VkDescriptorSet s_count[2], s_scatter[2];
  for (int i = 0; i < 2; ++i) {  // pass p reads array p % 2 and writes the other
    s_count[i] = pool.bind(k_count, {&key[i], &counts});
    s_scatter[i] = pool.bind(k_scatter, {&key[i], &value[i], &offsets, &key[1 - i], &value[1 - i]});
  }
  const uint32_t passes = radix_passes(cells);  // keys run up to `cells` (not a point)
  vk::submit(ctx, "fast method: cell sort", [&](VkCommandBuffer cmd) {
    KeyPush kp{0, 0, g.nx, g.ny, g.nz, 0, g.cell};
    vk::dispatch(ctx, cmd, k_key, s_key, &kp, 0, nv, kLocal);
    vk::barrier(cmd);
    for (uint32_t p = 0; p < passes; ++p) {
      RadixPush rp{0, 0, nv, 8 * p, p == 0};
      vk::dispatch(ctx, cmd, k_count, s_count[p % 2], &rp, 0, tiles, kLocal);
      vk::barrier(cmd);
      scan(cmd, k_scan, s_digits, digits);
      vk::barrier(cmd);
      vk::dispatch(ctx, cmd, k_scatter, s_scatter[p % 2], &rp, 0, tiles, kLocal);
      vk::barrier(cmd);
    }
  });

  // The occupied cells and their pieces, from the sorted keys (linear in the points).
  std::vector<uint32_t> sorted_key(np);
  key[passes % 2].download(sorted_key.data(), size_t(np) * 4);
  std::vector<uint32_t> piece_start, piece_cell, cell_piece;
  piece_start.reserve(np / 2 + 2);
  for (uint32_t i = 0; i < np;) {
    uint32_t e = i + 1;
    while (e < np && sorted_key[e] == sorted_key[i]) ++e;
    if (sorted_key[i] >= cells)
      throw Error("internal: the GPU fast method's cell sort left a vertex that is not a mesh point "
                  "among the mesh points");
    cell_piece.push_back(uint32_t(piece_start.size()));
    for (uint32_t b = i; b < e; b += kFastPiece) {
      piece_start.push_back(b);
      piece_cell.push_back(uint32_t(cell_piece.size() - 1));
    }
    i = e;
  }
  FastCells fc;
  fc.cells = uint32_t(cell_piece.size());
  fc.pieces = uint32_t(piece_start.size());
  cell_piece.push_back(fc.pieces);
  piece_start.push_back(np);

  fc.order = std::move(value[passes % 2]);
  fc.piece_start = vk::Buffer(ctx, piece_start.size() * 4, "the fast method's pieces");
  fc.piece_cell = vk::Buffer(ctx, piece_cell.size() * 4, "the fast method's pieces");
  vk::Buffer cell_piece_buf(ctx, cell_piece.size() * 4, "the fast method's pieces");
  vk::Buffer piece_sum(ctx, size_t(fc.pieces) * 32, "the fast method's piece sums");
  fc.cell_pos = vk::Buffer(ctx, size_t(fc.cells) * 32, "the fast method's cell centroids");
  fc.cell_count = vk::Buffer(ctx, size_t(fc.cells) * 8, "the fast method's cell counts");
  fc.piece_start.upload(piece_start.data(), piece_start.size() * 4);
  fc.piece_cell.upload(piece_cell.data(), piece_cell.size() * 4);
  cell_piece_buf.upload(cell_piece.data(), cell_piece.size() * 4);

  auto& k_pieces = vk::cached_kernel(ctx, spv_fast_aggregate_pieces_comp,
                                     sizeof spv_fast_aggregate_pieces_comp, 5, sizeof(RangePush),
                                     "fast_aggregate_pieces");
  auto& k_cells = vk::cached_kernel(ctx, spv_fast_aggregate_cells_comp,
                                    sizeof spv_fast_aggregate_cells_comp, 5, sizeof(CellsPush),
                                    "fast_aggregate_cells");
  VkDescriptorSet s_pieces =
      pool.bind(k_pieces, {in.pos, in.pos32, &fc.order, &fc.piece_start, &piece_sum});
  VkDescriptorSet s_cells = pool.bind(
      k_cells, {&piece_sum, &fc.piece_start, &cell_piece_buf, &fc.cell_pos, &fc.cell_count});
  vk::submit(ctx, "fast method: cell aggregates", [&](VkCommandBuffer cmd) {
    RangePush pp{0, 0};
    vk::dispatch(ctx, cmd, k_pieces, s_pieces, &pp, 0, fc.pieces, kLocal);
    vk::barrier(cmd);
    CellsPush cp{0, 0, 0, 0, {box_min[0], box_min[1], box_min[2]}};
    vk::dispatch(ctx, cmd, k_cells, s_cells, &cp, 0, fc.cells, kLocal);
  });
  return fc;
}

}  // namespace meshsal::gpu
