// meshsal: which vertices are "mesh points" (referenced by a triangle) and the scale unit eps.
#pragma once
#include <cstdint>
#include <vector>

#include "meshsal/meshsal.h"

namespace meshsal {

// 1 for every vertex referenced by at least one triangle, else 0 (SPEC 1, "Mesh points").
std::vector<uint8_t> referenced_vertices(const Mesh& mesh);

// The same from `count` indices over `vertex_count` vertices, on every core; an index
// >= vertex_count (a mesh not yet validated) marks nothing. *any (if given): whether some
// index was in range.
std::vector<uint8_t> referenced_mask(const uint32_t* indices, size_t count, size_t vertex_count,
                                     bool* any = nullptr);

// Axis-aligned bounding box; empty (min > max) when it holds no point.
struct BoundingBox {
  double min[3];
  double max[3];
  double diagonal() const;
  bool empty() const { return !(min[0] <= max[0]); }
};

// The bounding box of the finite coordinates of the vertices v with mask[v] != 0 (of every
// vertex when mask is null): one loop for the float positions and the doubles as read.
BoundingBox bounding_box(const float* xyz, size_t vertex_count, const uint8_t* mask);
BoundingBox bounding_box(const double* xyz, size_t vertex_count, const uint8_t* mask);

// Axis-aligned bounding box of the mesh points. Throws Error if there are none.
BoundingBox mesh_points_bbox(const Mesh& mesh, const std::vector<uint8_t>& is_point);

// eps = eps_frac * |bbox diagonal| over the mesh points (SPEC 1, "Scale unit").
double scale_unit(const Mesh& mesh, const std::vector<uint8_t>& is_point, double eps_frac);

}  // namespace meshsal
