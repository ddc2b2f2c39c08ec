// meshsal (internal): the tile grid, see tile_grid.h.
#include "tiles/tile_grid.h"

#include <algorithm>
#include <cmath>

namespace meshsal {
namespace detail {

TileGrid::TileGrid(const BoundingBox& box, unsigned tiles, double shift) : shift_(shift) {
  double longest = 0;
  for (int k = 0; k < 3; ++k) longest = std::max(longest, box.max[k] - box.min[k]);
  const double size = longest > 0 ? longest / tiles : 1;
  inv_size_ = 1 / size;
  for (int k = 0; k < 3; ++k) {
    min_[k] = box.min[k];
    // The last tile along an axis takes the points on the box's far face.
    cells_[k] = std::max<int64_t>(1, int64_t(std::ceil((box.max[k] - box.min[k]) * inv_size_ + shift)));
  }
}

uint64_t TileGrid::cell_of(const double p[3]) const {
  uint64_t id = 0;
  for (int k = 2; k >= 0; --k) {
    const double x = std::floor((p[k] - min_[k]) * inv_size_ + shift_);
    const int64_t i = x < 0 ? 0 : x >= double(cells_[k]) ? cells_[k] - 1 : int64_t(x);
    id = id * uint64_t(cells_[k]) + uint64_t(i);
  }
  return id;
}

BoundingBox TileGrid::cell_box(uint64_t id) const {
  BoundingBox b;
  for (int k = 0; k < 3; ++k) {
    const double i = double(id % uint64_t(cells_[k]));
    id /= uint64_t(cells_[k]);
    b.min[k] = min_[k] + (i - shift_) / inv_size_;
    b.max[k] = min_[k] + (i + 1 - shift_) / inv_size_;
  }
  return b;
}

uint64_t TileGrid::centroid_cell(const float* a, const float* b, const float* c) const {
  double m[3];
  for (int k = 0; k < 3; ++k) m[k] = ((double(a[k]) + b[k]) + c[k]) / 3;
  return cell_of(m);
}

std::vector<std::pair<uint64_t, uint32_t>> triangles_by_cell(const Mesh& mesh, const std::vector<uint32_t>& triangles,
                                                             const TileGrid& grid) {
  std::vector<std::pair<uint64_t, uint32_t>> cells;
  cells.reserve(triangles.size());
  for (uint32_t t : triangles) {
    const uint32_t* v = &mesh.triangles[3 * size_t(t)];
    cells.push_back({grid.centroid_cell(&mesh.positions[3 * size_t(v[0])], &mesh.positions[3 * size_t(v[1])],
                                        &mesh.positions[3 * size_t(v[2])]),
                     t});
  }
  std::sort(cells.begin(), cells.end());
  return cells;
}

}  // namespace detail
}  // namespace meshsal
