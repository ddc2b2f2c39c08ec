// meshsal: the uniform grid of the neighbour sweep: mesh points sorted by cell (x fastest),
// so that each row of cells along x is one contiguous range of points.
#pragma once
#include <cstdint>
#include <vector>

#include "meshsal/meshsal.h"

namespace meshsal {

struct SpatialGrid {
  double origin[3];                 // bbox minimum of the points
  double cell;                      // cell edge length
  int dims[3];                      // cells per axis
  std::vector<uint32_t> cell_start; // dims[0]*dims[1]*dims[2] + 1 offsets into the sorted arrays
  std::vector<uint32_t> order;      // sorted slot -> vertex index
  // Sorted point data relative to origin, padded by 4 far-away points so 4-wide loads
  // past a range stay in bounds.
  std::vector<double> x, y, z;
};

// The grid-size rule, one for the CPU and GPU grids: cells of `min_cell`, grown by 1.25
// while the grid (floor(extent / cell) + 1 per axis) would have more than
// max(2^20, 4 points) cells, or more than `cell_limit` (what one device buffer holds).
double grid_cell_size(const double extent[3], double min_cell, uint64_t points,
                      double cell_limit = 1e300);

// Grid over the vertices flagged in is_point, with cells of at least `min_cell` (grown when
// needed to keep the cell count near the point count, which keeps memory bounded).
SpatialGrid build_spatial_grid(const Mesh& mesh, const std::vector<uint8_t>& is_point,
                               double min_cell);

}  // namespace meshsal
