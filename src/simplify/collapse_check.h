// meshsal (internal): whether an edge collapse keeps the surface a manifold without folds.
// The link condition (the common neighbours of the two ends are exactly the vertices
// opposite the edge), no non-manifold or over-target collapse, no triangle that flips,
// folds or degenerates where the survivor moves, and on a seamed mesh the link condition
// on the welded surface too.
#pragma once
#include <cstdint>
#include <vector>

#include "simplify/seam_groups.h"
#include "simplify/triangle_fans.h"
#include "simplify/vertex_marks.h"
#include "simplify/vertex_record.h"

namespace meshsal {
namespace detail {

enum class Check { Ok, NotEdge, Refused };

// What the check reads of the surface (and the scratch it marks vertices in).
struct CheckSurface {
  TriangleFans* fans;          // compacted on the way
  const VertexRecord* vert;    // positions
  const uint8_t* border;       // per vertex: on an open border or a non-manifold edge
  SeamGroups* seams;           // null without seams
  VertexMarks* marks;
  size_t faces;                // live triangles
  size_t target;               // the face count not to go below
  double min_cos;              // SimplifyOptions::min_normal_cos
};

class CollapseCheck {
 public:
  // b into a, the survivor at np; along a seam edge both sides at once.
  Check edge(const CheckSurface& s, uint32_t a, uint32_t b, const double np[3]);
  // One side: b into a. seam_side: one side of a seam edge (it must be a border edge).
  Check side(const CheckSurface& s, uint32_t a, uint32_t b, const double np[3], bool seam_side);

 private:
  // Would triangle t, with vertex `moved` placed at np, flip, fold or degenerate?
  static bool bad_triangle(const CheckSurface& s, uint32_t t, uint32_t moved, const double np[3]);
  // Sized to the largest fan seen: the vertices opposite the edge, and the triangles of
  // each end that stay (the flip tests).
  std::vector<uint32_t> opp_, flip_a_, flip_b_;
};

}  // namespace detail
}  // namespace meshsal
