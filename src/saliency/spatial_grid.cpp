#include "saliency/spatial_grid.h"

#include <algorithm>
#include <cmath>

#include "meshsal/meshsal.h"
#include "core/mesh_points.h"

namespace meshsal {

double grid_cell_size(const double extent[3], double min_cell, uint64_t points,
                      double cell_limit) {
  // A few cells per point, at least 2^20: memory stays bounded on a tiny cell.
  const double max_cells = std::min(std::max<double>(1 << 20, 4.0 * double(points)), cell_limit);
  double cell = min_cell;
  for (;;) {
    double cells = 1;
    for (int a = 0; a < 3; ++a) cells *= std::floor(extent[a] / cell) + 1;
    if (cells <= max_cells) return cell;
    cell *= 1.25;
  }
}

SpatialGrid build_grid_order(const Mesh& mesh, const std::vector<uint8_t>& is_point,
                             double min_cell, const GridFrame* frame, double cell_limit) {
  SpatialGrid g;
  size_t points = 0;
  for (uint8_t f : is_point) points += f;
  if (points >= UINT32_MAX) throw Error("too many mesh points for the grid (4 billion)");
  // The whole grid's origin, cell and cell count per axis: this mesh's, or the frame's.
  const BoundingBox box = frame ? frame->box : mesh_points_bbox(mesh, is_point);
  double extent[3];
  for (int a = 0; a < 3; ++a) extent[a] = box.max[a] - box.min[a];
  const double cell = grid_cell_size(extent, min_cell, frame ? frame->points : points, cell_limit);
  g.cell = cell;
  int whole[3];
  for (int a = 0; a < 3; ++a) {
    g.origin[a] = box.min[a];
    whole[a] = int(std::floor((box.max[a] - box.min[a]) / cell)) + 1;
  }
  const size_t n = mesh.vertex_count();
  auto cell_of = [&](size_t v, int a) {
    return std::min(whole[a] - 1, int((double(mesh.positions[3 * v + a]) - g.origin[a]) / cell));
  };
  // The cells held: all of them, or (a tile) those from the lowest to the highest its
  // points fall in.
  for (int a = 0; a < 3; ++a) {
    g.lo[a] = 0;
    g.dims[a] = whole[a];
  }
  if (frame) {
    int hi[3] = {-1, -1, -1};
    for (int a = 0; a < 3; ++a) g.lo[a] = whole[a];
    for (size_t v = 0; v < n; ++v)
      if (is_point[v])
        for (int a = 0; a < 3; ++a) {
          g.lo[a] = std::min(g.lo[a], cell_of(v, a));
          hi[a] = std::max(hi[a], cell_of(v, a));
        }
    for (int a = 0; a < 3; ++a) {
      if (hi[a] < g.lo[a]) g.lo[a] = hi[a] = 0;  // no point
      g.dims[a] = hi[a] - g.lo[a] + 1;
    }
  }
  const size_t ncells = size_t(g.dims[0]) * g.dims[1] * g.dims[2];

  // Counting sort of the points by cell key, in place (no key or cursor arrays: the key is
  // computed twice, and the points are placed from the back, each cell's end counting down
  // to its start), stable: within a cell the points keep vertex order.
  auto key_of = [&](size_t v) {
    int c[3];
    for (int a = 0; a < 3; ++a) c[a] = cell_of(v, a) - g.lo[a];
    return (size_t(c[2]) * g.dims[1] + c[1]) * g.dims[0] + c[0];
  };
  g.cell_start.assign(ncells + 1, 0);
  for (size_t v = 0; v < n; ++v)
    if (is_point[v]) g.cell_start[key_of(v) + 1]++;
  for (size_t c = 0; c < ncells; ++c) g.cell_start[c + 1] += g.cell_start[c];
  g.order.resize(points);
  for (size_t v = n; v-- > 0;)
    if (is_point[v]) g.order[--g.cell_start[key_of(v) + 1]] = uint32_t(v);
  // cell_start[c + 1] now holds cell c's start: shift down by one, the end last.
  std::copy(g.cell_start.begin() + 1, g.cell_start.end(), g.cell_start.begin());
  g.cell_start[ncells] = uint32_t(points);
  return g;
}

SpatialGrid build_spatial_grid(const Mesh& mesh, const std::vector<uint8_t>& is_point,
                               double min_cell, const GridFrame* frame) {
  SpatialGrid g = build_grid_order(mesh, is_point, min_cell, frame);
  const size_t points = g.order.size();
  const double far = 1e300;  // padding points never pass a distance test
  g.x.assign(points + 4, far);
  g.y.assign(points + 4, far);
  g.z.assign(points + 4, far);
  for (size_t s = 0; s < points; ++s) {
    uint32_t v = g.order[s];
    g.x[s] = double(mesh.positions[3 * v]) - g.origin[0];
    g.y[s] = double(mesh.positions[3 * v + 1]) - g.origin[1];
    g.z[s] = double(mesh.positions[3 * v + 2]) - g.origin[2];
  }
  return g;
}

}  // namespace meshsal
