// meshsal (internal): what a collapse reads of each vertex, in one record.
#pragma once
#include "simplify/quadric.h"

namespace meshsal {
namespace detail {

// Two cache lines of one record instead of a miss in each of three arrays.
struct alignas(64) VertexRecord {
  Quadric q;
  // Sum of the plane weights in q (triangle areas, border weights, times W): the collapse
  // error sqrt(Q(v) / weight) is a distance (target_error).
  double plane_weight;
  double p[3];  // internal coordinates
};

}  // namespace detail
}  // namespace meshsal
