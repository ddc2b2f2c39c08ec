// meshsal: --method fast, sorting and aggregating the cells on the device (gpu_fast_cells.h).
#include "gpu/gpu_fast_cells.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "meshsal/meshsal.h"
#include "gpu/gpu_radix_sort.h"
#include "gpu/shader_interfaces.h"
#include "gpu/vk_compute.h"

#include "fast_aggregate_cells_comp.h"
#include "fast_aggregate_pieces_comp.h"
#include "fast_cell_key_comp.h"

namespace meshsal::gpu {

namespace {
constexpr uint32_t kLocal = 64;  // local_size_x of the shaders
using shader::CellKeyPush;  // the push blocks: gpu/shader_interfaces.h
using shader::CellsPush;
using shader::RangePush;
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
  const uint64_t sort = RadixSort::bytes(nv);
  const uint64_t pieces = np + np / kFastPiece + 1;  // at most
  return sort + pieces * (4 + 4 + 32) + np * (4 + 32 + 8);    // piece arrays and sums, cells
}

FastCells aggregate_cells(vk::Context& ctx, const FastInputs& in, uint32_t nv, uint32_t np,
                          const FastGrid& g, const double box_min[3]) {
  const uint32_t cells = g.nx * g.ny * g.nz;
  auto& k_key = vk::cached_kernel<shader::FastCellKey>(ctx, spv_fast_cell_key_comp, sizeof spv_fast_cell_key_comp, "fast_cell_key");
  vk::DescriptorPool pool(ctx, 8, 32);
  RadixSort sort(ctx, pool, nv, cells, "the fast method's");  // keys run up to `cells` (not a point)
  VkDescriptorSet s_key = pool.bind(k_key, {in.pos, in.flags, &sort.keys_in()});
  vk::submit(ctx, "fast method: cell sort", [&](VkCommandBuffer cmd) {
    CellKeyPush kp{0, 0, g.nx, g.ny, g.nz, 0, g.cell};
    vk::dispatch(ctx, cmd, k_key, s_key, &kp, 0, nv, kLocal);
    vk::barrier(cmd);
    sort.record(ctx, cmd);
  });

  // The occupied cells and their pieces, from the sorted keys (linear in the points).
  std::vector<uint32_t> sorted_key(np);
  sort.sorted_keys().download(sorted_key.data(), size_t(np) * 4);
  std::vector<uint32_t> piece_start, piece_cell, cell_piece, cell_key;
  piece_start.reserve(np / 2 + 2);
  for (uint32_t i = 0; i < np;) {
    uint32_t e = i + 1;
    while (e < np && sorted_key[e] == sorted_key[i]) ++e;
    if (sorted_key[i] >= cells)
      throw Error("internal: the GPU fast method's cell sort left a vertex that is not a mesh point "
                  "among the mesh points");
    cell_piece.push_back(uint32_t(piece_start.size()));
    cell_key.push_back(sorted_key[i]);
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

  fc.cell_key = std::move(cell_key);
  fc.order = std::move(sort.order());
  fc.piece_start = vk::Buffer(ctx, piece_start.size() * 4, "the fast method's pieces");
  fc.piece_cell = vk::Buffer(ctx, piece_cell.size() * 4, "the fast method's pieces");
  vk::Buffer cell_piece_buf(ctx, cell_piece.size() * 4, "the fast method's pieces");
  vk::Buffer piece_sum(ctx, size_t(fc.pieces) * 32, "the fast method's piece sums");
  fc.cell_pos = vk::Buffer(ctx, size_t(fc.cells) * 32, "the fast method's cell centroids");
  fc.cell_count = vk::Buffer(ctx, size_t(fc.cells) * 8, "the fast method's cell counts");
  fc.piece_start.upload(piece_start.data(), piece_start.size() * 4);
  fc.piece_cell.upload(piece_cell.data(), piece_cell.size() * 4);
  cell_piece_buf.upload(cell_piece.data(), cell_piece.size() * 4);

  auto& k_pieces = vk::cached_kernel<shader::FastAggregatePieces>(ctx, spv_fast_aggregate_pieces_comp, sizeof spv_fast_aggregate_pieces_comp, "fast_aggregate_pieces");
  auto& k_cells = vk::cached_kernel<shader::FastAggregateCells>(ctx, spv_fast_aggregate_cells_comp, sizeof spv_fast_aggregate_cells_comp, "fast_aggregate_cells");
  VkDescriptorSet s_pieces =
      pool.bind(k_pieces, {in.pos, in.pos32, &fc.order, &fc.piece_start, &piece_sum});
  VkDescriptorSet s_cells = pool.bind(
      k_cells, {&piece_sum, &fc.piece_start, &cell_piece_buf, &fc.cell_pos, &fc.cell_count});
  vk::submit(ctx, "fast method: cell aggregates", [&](VkCommandBuffer cmd) {
    RangePush pp{0, 0};
    vk::dispatch(ctx, cmd, k_pieces, s_pieces, &pp, 0, fc.pieces, kLocal);
    vk::barrier(cmd);
    CellsPush cp{0, 0, 0, 0, box_min[0], box_min[1], box_min[2]};
    vk::dispatch(ctx, cmd, k_cells, s_cells, &cp, 0, fc.cells, kLocal);
  });
  return fc;
}

}  // namespace meshsal::gpu
