// meshsal: --method fast on the device, first stage per sigma: the GPU twin of
// sort_into_cells() (src/saliency/sparse_cells.cpp) and aggregate() (gaussian_filter_fast.cpp).
// The mesh points are sorted by the cell of edge `cell` they fall in (a stable radix sort
// of the dense cell indices of fast_cell_key.comp, the CPU's cell_key() values, so that
// inside a cell they stay in vertex order, as on the CPU) and each occupied cell gets its
// point count, value sum and centroid (rounded to float, as the CPU rounds it).
#pragma once
#include <cstdint>
#include <vector>

#include "gpu/vk_buffer.h"
#include "gpu/vk_context.h"

namespace meshsal::gpu {

// Points per piece: a cell's points are summed in pieces of at most this many, one lane
// each, so that no invocation loops past lavapipe's 65,535 steps.
constexpr uint32_t kFastPiece = 4096;

// One sigma's aggregates on the device.
struct FastCells {
  uint32_t cells = 0;    // occupied cells (m)
  uint32_t pieces = 0;   // pieces of at most kFastPiece points, in sorted order
  vk::Buffer order;        // sorted slot -> vertex (the mesh points come first)
  vk::Buffer piece_start;  // pieces + 1: piece p holds sorted slots [start[p], start[p+1])
  vk::Buffer piece_cell;   // pieces: the cell of piece p
  vk::Buffer cell_pos;     // dvec4 per cell: float centroid - bbox min (in double), value sum
  vk::Buffer cell_count;   // double per cell: its point count
  std::vector<uint32_t> cell_key;  // per cell, on the host: its key (the CPU's cell_key())
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
};
FastGrid plan_fast_grid(const double extent[3], double cell);

// Sorts the nv vertices (np of them mesh points) into the cells of `grid` and aggregates
// every occupied cell.
FastCells aggregate_cells(vk::Context& ctx, const FastInputs& in, uint32_t nv, uint32_t np,
                          const FastGrid& grid, const double box_min[3]);

// Device bytes aggregate_cells() holds at its peak (its scratch and its FastCells).
uint64_t fast_cells_bytes(uint64_t nv, uint64_t np);

}  // namespace meshsal::gpu
