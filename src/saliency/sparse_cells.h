// meshsal: mesh points sorted by the sparse cell they fall in (only occupied cells exist,
// so a fine cell on a long mesh costs nothing): the fast method's per-sigma aggregates and
// its pair estimate start from it.
#pragma once
#include <cstdint>
#include <vector>

#include "core/mesh_points.h"
#include "meshsal/meshsal.h"

namespace meshsal {

struct SparseCells {
  std::vector<uint32_t> order;  // sorted slot -> vertex
  std::vector<uint32_t> start;  // occupied cell c holds slots start[c] .. start[c+1]-1
  std::vector<uint64_t> key;    // occupied cell c's key (cell_key), ascending
  uint64_t dims[3];             // cells per axis
};

// Cell edge of at least `cell`, grown until every axis has fewer than 2^21 cells (so that
// a key fits in 63 bits). The GPU fast method (gpu/gpu_fast.cpp) calls it too, so that
// both paths take the same cells.
double usable_cell(const BoundingBox& box, double cell);

// The cell of p as one number, z slowest: (z * dims[1] + y) * dims[0] + x, so that keys
// order the cells by z, then y, then x. Cells start at box.min.
void cell_dims(const BoundingBox& box, double cell, uint64_t dims[3]);
uint64_t cell_key(const BoundingBox& box, double cell, const uint64_t dims[3], const float* p);

// The distinct cell keys of the points `xyz` (3 floats each, n of them), ascending: what
// sort_into_cells(...).key holds, without the order of the points. Through a bitmap over
// the cells of `within` (a box that holds every point) where it takes at most
// `bitmap_bytes_per_point` bytes a point (one pass and a scan instead of a sort), else by
// sorting (0: always).
std::vector<uint64_t> distinct_cell_keys(const float* xyz, size_t n, const BoundingBox& box, double cell,
                                         const BoundingBox& within, double bitmap_bytes_per_point = 16,
                                         unsigned threads = 0);

// The mesh points (is_point) in vertex order.
std::vector<uint32_t> mesh_point_list(const std::vector<uint8_t>& is_point);

// `points` (vertex indices) sorted by cell key, within a cell in the order given. Keys
// are computed on `threads` threads and sorted by a stable radix sort (linear).
SparseCells sort_into_cells(const Mesh& mesh, const std::vector<uint32_t>& points,
                            const BoundingBox& box, double cell, unsigned threads = 0);
// The same, taking the list over (it becomes the result's order: 4 bytes per point less).
SparseCells sort_into_cells(const Mesh& mesh, std::vector<uint32_t>&& points, const BoundingBox& box,
                            double cell, unsigned threads = 0);

// The same with std::stable_sort: the oracle the tests hold sort_into_cells to.
SparseCells sort_into_cells_reference(const Mesh& mesh, const std::vector<uint32_t>& points,
                                      const BoundingBox& box, double cell);

}  // namespace meshsal
