// meshsal: --method fast, sorting and aggregating the cells on the device (gpu_fast_cells.h).
#include "gpu/gpu_fast_cells.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "meshsal/meshsal.h"
#include "gpu/shader_interfaces.h"

#include "fast_aggregate_cells_comp.h"
#include "fast_aggregate_pieces_comp.h"
#include "fast_cell_key_comp.h"
#include "fast_pieces_comp.h"

namespace meshsal::gpu {

namespace {
constexpr uint32_t kLocal = 64;  // local_size_x of the shaders
using shader::CellKeyPush;  // the push blocks: gpu/shader_interfaces.h
using shader::CellsPush;
using shader::CountedPush;
using shader::PiecesPush;
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

FastRuns fast_cell_runs(const std::vector<uint32_t>& sorted_key, uint32_t np, uint64_t cells,
                        uint32_t piece) {
  FastRuns r;
  for (uint32_t i = 0; i < np;) {
    uint32_t e = i + 1;
    while (e < np && sorted_key[e] == sorted_key[i]) ++e;
    if (sorted_key[i] >= cells)
      throw Error("internal: the GPU fast method's cell sort left a vertex that is not a mesh point "
                  "among the mesh points");
    r.cell_piece.push_back(uint32_t(r.piece_start.size()));
    r.cell_key.push_back(sorted_key[i]);
    for (uint32_t b = i; b < e; b += piece) {
      r.piece_start.push_back(b);
      r.piece_cell.push_back(uint32_t(r.cell_key.size() - 1));
    }
    i = e;
  }
  r.cell_piece.push_back(uint32_t(r.piece_start.size()));
  r.piece_start.push_back(np);
  return r;
}

uint64_t fast_cells_bytes(uint64_t nv, uint64_t np) {
  const uint64_t sort = RadixSort::bytes(nv);
  const uint64_t pieces = np + np / kFastPiece + 2;  // at most
  // pieces: start, cell, sum; cells: key, first, piece, centroid, count, flag; slots:
  // heads and scans of the cells and the pieces
  return sort + pieces * (4 + 4 + 32) + np * (4 + 4 + 4 + 32 + 8 + 4) + np * 16 + 2 * Scan::bytes(np);
}

namespace {
// At most a piece per cell and one more per `piece` points: np + np / piece.
size_t max_pieces(uint32_t np, uint32_t piece) { return size_t(np) + np / piece; }
uint32_t checked_points(uint32_t np, uint32_t piece) {
  if (np == 0 || piece == 0) throw Error("internal: the GPU fast cells need a mesh point and a piece size");
  return np;
}
}  // namespace

FastCells::FastCells(vk::Context& ctx, vk::DescriptorPool& pool, const FastInputs& in,
                     vk::Buffer& counts, uint32_t nv, uint32_t np, uint64_t most_cells, uint32_t piece)
    : cell_key(ctx, size_t(checked_points(np, piece)) * 4, "the fast method's cell keys"),
      cell_first(ctx, size_t(np + 1) * 4, "the fast method's cell starts"),
      cell_piece(ctx, size_t(np + 1) * 4, "the fast method's pieces"),
      cell_pos(ctx, size_t(np) * 32, "the fast method's cell centroids"),
      cell_count(ctx, size_t(np) * 8, "the fast method's cell counts"),
      is_cell(ctx, size_t(np) * 4, "the fast method's cell flags"),
      piece_start(ctx, (max_pieces(np, piece) + 1) * 4, "the fast method's pieces"),
      piece_cell(ctx, max_pieces(np, piece) * 4, "the fast method's pieces"),
      nv_(nv), np_(np), piece_(piece),
      // keys run up to the grid's cell count (a vertex that is not a mesh point)
      sort_(ctx, pool, nv, most_cells, "the fast method's"),
      head_(ctx, size_t(np) * 4, "the fast method's run heads"),
      scan_(ctx, size_t(np + 1) * 4, "the fast method's run scan"),
      piece_head_(ctx, size_t(np) * 4, "the fast method's piece heads"),
      piece_scan_(ctx, size_t(np + 1) * 4, "the fast method's piece scan"),
      piece_sum_(ctx, max_pieces(np, piece) * 32, "the fast method's piece sums"),
      runs_(ctx, pool, {&sort_.sorted_keys(), &counts, &head_, &scan_, &cell_first, &cell_key}, np),
      piece_scan_step_(ctx, pool, piece_head_, piece_scan_, np) {
  k_key_ = &vk::cached_kernel<shader::FastCellKey>(ctx, spv_fast_cell_key_comp, sizeof spv_fast_cell_key_comp, "fast_cell_key");
  k_pieces_ = &vk::cached_kernel<shader::FastPieces>(ctx, spv_fast_pieces_comp, sizeof spv_fast_pieces_comp, "fast_pieces");
  k_sum_pieces_ = &vk::cached_kernel<shader::FastAggregatePieces>(ctx, spv_fast_aggregate_pieces_comp, sizeof spv_fast_aggregate_pieces_comp, "fast_aggregate_pieces");
  k_sum_cells_ = &vk::cached_kernel<shader::FastAggregateCells>(ctx, spv_fast_aggregate_cells_comp, sizeof spv_fast_aggregate_cells_comp, "fast_aggregate_cells");
  s_key_ = pool.bind(*k_key_, {in.pos, in.flags, &sort_.keys_in()});
  s_pieces_ = pool.bind(*k_pieces_, {&scan_, &cell_first, &piece_head_, &piece_scan_, &piece_start,
                                     &piece_cell, &cell_piece, &counts});
  s_sum_pieces_ = pool.bind(*k_sum_pieces_, {in.pos, in.pos32, &sort_.order(), &piece_start, &piece_sum_, &counts});
  s_sum_cells_ = pool.bind(*k_sum_cells_, {&piece_sum_, &piece_start, &cell_piece, &cell_pos, &cell_count,
                                           &counts, &is_cell});
}

void FastCells::record(vk::Context& ctx, VkCommandBuffer cmd, const FastGrid& g, const double box_min[3]) {
  CellKeyPush kp{0, 0, g.nx, g.ny, g.nz, 0, g.cell};
  vk::dispatch(ctx, cmd, *k_key_, s_key_, &kp, 0, nv_, kLocal);
  vk::barrier(cmd);
  sort_.record(ctx, cmd);
  // The cells: the runs of the np sorted keys (the mesh points sort first).
  runs_.record(ctx, cmd, np_, kCountIsN, kCountCells, kRunKeys);
  // Their pieces: heads, a scan, where each starts.
  PiecesPush pp{0, 0, 0, piece_, kCountPieces};
  vk::dispatch(ctx, cmd, *k_pieces_, s_pieces_, &pp, 0, np_, kLocal);
  vk::barrier(cmd);
  piece_scan_step_.record(ctx, cmd, np_);
  pp.mode = 1;
  vk::dispatch(ctx, cmd, *k_pieces_, s_pieces_, &pp, 0, np_, kLocal);
  vk::barrier(cmd);
  // The sums: per piece, then per cell (over the bounds; the shaders stop at the counts).
  CountedPush sp{0, 0, kCountPieces};
  vk::dispatch(ctx, cmd, *k_sum_pieces_, s_sum_pieces_, &sp, 0, uint32_t(max_pieces(np_, piece_)), kLocal);
  vk::barrier(cmd);
  CellsPush cp{0, 0, kCountCells, 0, box_min[0], box_min[1], box_min[2]};
  vk::dispatch(ctx, cmd, *k_sum_cells_, s_sum_cells_, &cp, 0, np_, kLocal);
  vk::barrier(cmd);
}

}  // namespace meshsal::gpu
