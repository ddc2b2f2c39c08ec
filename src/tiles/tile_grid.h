// meshsal (internal): the cubic tiles of tiled simplification (simplify_tiled.cpp).
#pragma once
#include <cstdint>
#include <utility>
#include <vector>

#include "core/mesh_points.h"
#include "meshsal/meshsal.h"

namespace meshsal {
namespace detail {

// `tiles` cubes along the longest axis of `box`, the grid anchored at box.min; `shift` 0.5
// moves every cut by half a tile (the strips' grid: its cuts fall mid-way between the first
// grid's). A point outside the box goes to the nearest tile.
class TileGrid {
 public:
  TileGrid(const BoundingBox& box, unsigned tiles, double shift);
  uint64_t cell_of(const double p[3]) const;
  // The cell of the centroid of the triangle with corners a, b, c (the triangle's tile).
  uint64_t centroid_cell(const float* a, const float* b, const float* c) const;
  // Cells along x, y, z, and a cell's box (the out-of-core driver sizes its tiles by them).
  const int64_t* cells() const { return cells_; }
  BoundingBox cell_box(uint64_t id) const;

 private:
  double min_[3];
  double inv_size_;
  double shift_;
  int64_t cells_[3];
};

// Tiles and their triangles: (cell, triangle) for each triangle of `mesh` listed in
// `triangles` (indices into mesh.triangles / 3), the cell being that of its centroid, sorted
// by cell and then triangle. A centroid is never on two sides of a cut, so each triangle
// is in exactly one tile.
std::vector<std::pair<uint64_t, uint32_t>> triangles_by_cell(const Mesh& mesh, const std::vector<uint32_t>& triangles,
                                                             const TileGrid& grid);

}  // namespace detail
}  // namespace meshsal
