// meshsal: the uniform grid of the neighbour sweep: mesh points sorted by cell (x fastest),
// so that each row of cells along x is one contiguous range of points.
#pragma once
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "core/mesh_points.h"
#include "meshsal/meshsal.h"

namespace meshsal {

struct SpatialGrid {
  double origin[3];                 // bbox minimum of the points (of the whole mesh's, in a tile)
  double cell;                      // cell edge length
  int dims[3];                      // cells per axis
  // The first cell held, per axis: 0, except on a tile of a larger mesh (GridFrame), whose
  // grid holds only the cells its points fall in, numbered as in the whole mesh's grid.
  int lo[3] = {0, 0, 0};
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
  // Cell numbers of the whole grid; [lo, lo + dims) of them are held.
  const int zlo = std::max(g.lo[2], int(std::floor((z - R) / c)));
  const int zhi = std::min(g.lo[2] + g.dims[2] - 1, int(std::floor((z + R) / c)));
  const int ylo = std::max(g.lo[1], int(std::floor((y - R) / c)));
  const int yhi = std::min(g.lo[1] + g.dims[1] - 1, int(std::floor((y + R) / c)));
  for (int cz = zlo; cz <= zhi; ++cz) {
    const double dz = std::max({0.0, cz * c - z, z - (cz + 1) * c});
    for (int cy = ylo; cy <= yhi; ++cy) {
      const double dy = std::max({0.0, cy * c - y, y - (cy + 1) * c});
      const double rest = radius2 - dz * dz - dy * dy;
      if (rest <= 0) continue;
      const double hx = std::sqrt(rest);
      const int xlo = std::max(g.lo[0], int(std::floor((x - hx) / c)));
      const int xhi = std::min(g.lo[0] + g.dims[0] - 1, int(std::floor((x + hx) / c)));
      if (xlo > xhi) continue;
      const size_t first = (size_t(cz - g.lo[2]) * g.dims[1] + (cy - g.lo[1])) * g.dims[0];
      row(size_t(g.cell_start[first + (xlo - g.lo[0])]),
          size_t(g.cell_start[first + (xhi - g.lo[0]) + 1]));
    }
  }
}

// The whole mesh a tile belongs to (saliency_tiles.h): its mesh points' bounding box and
// count decide the grid's origin and cell, so that a tile's grid is a window of the whole
// mesh's and its sweeps visit the same points in the same order.
struct GridFrame {
  BoundingBox box;
  uint64_t points = 0;
};

// Grid over the vertices flagged in is_point, with cells of at least `min_cell` (grown when
// needed to keep the cell count near the point count, which keeps memory bounded). With a
// frame: the whole mesh's grid, holding only the cells that these points fall in.
SpatialGrid build_spatial_grid(const Mesh& mesh, const std::vector<uint8_t>& is_point,
                               double min_cell, const GridFrame* frame = nullptr);

// The same grid without the sorted coordinates (x, y, z stay empty): for a caller that
// keeps its own copy of them (the fast method's float aggregates). cell_limit: at most this
// many cells (grid_cell_size's).
SpatialGrid build_grid_order(const Mesh& mesh, const std::vector<uint8_t>& is_point,
                             double min_cell, const GridFrame* frame = nullptr,
                             double cell_limit = 1e300);

}  // namespace meshsal
