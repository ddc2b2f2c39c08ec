// meshsal: the uniform grid of the neighbour sweep: mesh points sorted by cell (x fastest),
// so that each row of cells along x is one contiguous range of points.
#pragma once
#include <algorithm>
#include <cmath>
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

// Calls row(jb, je) for every row of cells (along x) that the ball of squared radius
// `radius2` around (x, y, z) (relative to the grid origin) reaches: rows outside the ball
// are culled and each row is clipped to the ball's chord; [jb, je) are its sorted slots.
// The exact sweep and the fast method's cell sweep share it.
template <class Row>
inline void for_each_row_in_ball(const SpatialGrid& g, double x, double y, double z,
                                 double radius2, Row&& row) {
  const double R = std::sqrt(radius2), c = g.cell;
  const int zlo = std::max(0, int(std::floor((z - R) / c)));
  const int zhi = std::min(g.dims[2] - 1, int(std::floor((z + R) / c)));
  const int ylo = std::max(0, int(std::floor((y - R) / c)));
  const int yhi = std::min(g.dims[1] - 1, int(std::floor((y + R) / c)));
  for (int cz = zlo; cz <= zhi; ++cz) {
    const double dz = std::max({0.0, cz * c - z, z - (cz + 1) * c});
    for (int cy = ylo; cy <= yhi; ++cy) {
      const double dy = std::max({0.0, cy * c - y, y - (cy + 1) * c});
      const double rest = radius2 - dz * dz - dy * dy;
      if (rest <= 0) continue;
      const double hx = std::sqrt(rest);
      const int xlo = std::max(0, int(std::floor((x - hx) / c)));
      const int xhi = std::min(g.dims[0] - 1, int(std::floor((x + hx) / c)));
      const size_t first = (size_t(cz) * g.dims[1] + cy) * g.dims[0];
      row(size_t(g.cell_start[first + xlo]), size_t(g.cell_start[first + xhi + 1]));
    }
  }
}

// Grid over the vertices flagged in is_point, with cells of at least `min_cell` (grown when
// needed to keep the cell count near the point count, which keeps memory bounded).
SpatialGrid build_spatial_grid(const Mesh& mesh, const std::vector<uint8_t>& is_point,
                               double min_cell);

}  // namespace meshsal
