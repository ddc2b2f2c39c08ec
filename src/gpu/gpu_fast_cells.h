// meshsal: --method fast on the device, first stage per sigma: the GPU twin of
// sort_into_cells() (src/saliency/sparse_cells.cpp) and aggregate() (gaussian_filter_fast.cpp).
// The mesh points are sorted by the cell of edge `cell` they fall in (a stable radix sort
// of the dense cell indices of fast_cell_key.comp, the CPU's cell_key() values, so that
// inside a cell they stay in vertex order, as on the CPU), the occupied cells and their
// pieces found as runs of the sorted keys (run_heads.comp, run_starts.comp, fast_pieces.comp;
// host twin: fast_cell_runs()), and each cell gets its point count, value sum and centroid
// (rounded to float, as the CPU rounds it). All on the device: the host reads nothing back;
// the counts (cells, pieces) land in a counts buffer on the device, which the fast filter
// copies into host memory at the end of each sigma's preparation.
#pragma once
#include <cstdint>
#include <vector>

#include "gpu/gpu_radix_sort.h"
#include "gpu/gpu_runs.h"
#include "gpu/vk_buffer.h"
#include "gpu/vk_compute.h"
#include "gpu/vk_context.h"

namespace meshsal::gpu {

// Points per piece: a cell's points are summed in pieces of at most this many, one lane
// each, so that no invocation loops past lavapipe's 65,535 steps.
constexpr uint32_t kFastPiece = 4096;

// The slots of the fast filter's counts buffer (uint each): what the device found for the
// current sigma. The host reads them once per sigma (from a copy in host memory), after the
// submission that wrote them.
enum FastCount : uint32_t {
  kCountCells,           // occupied cells (m)
  kCountPieces,          // pieces of the cells
  kCountGroups,          // query groups (fast_gpu_groups.h)
  kCountMostCandidates,  // the most candidates any query walks (gpu_fast_bound.h)
  kFastCounts
};

// The device arrays the aggregation reads: pos (dvec4 per vertex: position - bbox min in
// double, value in w), flags (uint: mesh point or not) and pos32 (vec4: the input's float
// coordinates).
struct FastInputs {
  const vk::Buffer* pos = nullptr;
  const vk::Buffer* flags = nullptr;
  const vk::Buffer* pos32 = nullptr;
};

// The grid of cells of edge `cell` from box_min over extent[]: cells per axis, and whether
// their dense count fits the 32-bit keys (else Error, naming the CPU path).
struct FastGrid {
  uint32_t nx = 1, ny = 1, nz = 1;
  double cell = 1;
  uint64_t cells() const { return uint64_t(nx) * ny * nz; }
};
FastGrid plan_fast_grid(const double extent[3], double cell);

// The host twin of the run finding: from the sorted keys of the np mesh points (keys below
// `cells`), the occupied cells (their keys; cell_piece[c], c <= cells: the first piece of
// cell c, then the piece count) and their pieces of at most `piece` points counted from
// the cell's first point (piece_start[p], p <= pieces: its first sorted slot, then np;
// piece_cell[p]: its cell). The oracle the tests hold the device to.
struct FastRuns {
  std::vector<uint32_t> cell_key, cell_piece, piece_start, piece_cell;
};
FastRuns fast_cell_runs(const std::vector<uint32_t>& sorted_key, uint32_t np, uint64_t cells,
                        uint32_t piece = kFastPiece);

// One sigma's cells on the device, the arrays made once for every sigma of a filter: sized
// for nv vertices of which np are mesh points (np >= 1), over grids of at most most_cells
// cells (the finest sigma's: it sets the sort's passes).
class FastCells {
 public:
  FastCells(vk::Context& ctx, vk::DescriptorPool& pool, const FastInputs& in, vk::Buffer& counts,
            uint32_t nv, uint32_t np, uint64_t most_cells, uint32_t piece = kFastPiece);
  // Its descriptor sets name its own buffers: neither copied nor moved.
  FastCells(const FastCells&) = delete;
  FastCells& operator=(const FastCells&) = delete;
  // Records the sort and aggregation for `grid` into cmd, ending with a barrier: afterwards
  // the arrays below hold this sigma's cells and counts[kCountCells], [kCountPieces] theirs.
  void record(vk::Context& ctx, VkCommandBuffer cmd, const FastGrid& grid, const double box_min[3]);
  // The descriptor sets and buffers the constructor takes from its pool.
  static constexpr uint32_t kSets = RadixSort::kSets + RunFinder::kSets + Scan::kSets + 4;
  static constexpr uint32_t kBuffers = RadixSort::kBuffers + RunFinder::kBuffers + Scan::kBuffers + 24;

  uint32_t np() const { return np_; }
  vk::Buffer& order() { return sort_.order(); }  // sorted slot -> vertex (mesh points first)
  vk::Buffer& sorted_keys() { return sort_.sorted_keys(); }  // the cell key of each sorted slot
  // Per cell c < counts[kCountCells] (the buffers hold np): its key, its first sorted slot
  // (cell_first[cells] = np), its first piece (cell_piece[cells] = pieces), its centroid
  // (dvec4: float centroid - bbox min in double, value sum), its point count (double), and
  // is_cell (1 for the cells, 0 for the slots past them: the query grid's point flags).
  vk::Buffer cell_key, cell_first, cell_piece, cell_pos, cell_count, is_cell;
  // Per piece p < counts[kCountPieces]: its first sorted slot (piece_start[pieces] = np) and
  // its cell.
  vk::Buffer piece_start, piece_cell;

 private:
  uint32_t nv_, np_, piece_;
  RadixSort sort_;
  vk::Buffer head_, scan_, piece_head_, piece_scan_, piece_sum_;
  RunFinder runs_;
  Scan piece_scan_step_;
  const vk::Kernel *k_key_, *k_pieces_, *k_sum_pieces_, *k_sum_cells_;
  VkDescriptorSet s_key_, s_pieces_, s_sum_pieces_, s_sum_cells_;
};

// Device bytes FastCells holds for nv vertices, np of them mesh points.
uint64_t fast_cells_bytes(uint64_t nv, uint64_t np);

}  // namespace meshsal::gpu
