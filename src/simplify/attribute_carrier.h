// meshsal (internal): Mesh::attributes carried through the collapses. The vertex that stays
// takes values interpolated along the collapsed edge; a normal (nx ny nz) is renormalised
// on output.
#pragma once
#include <cstdint>
#include <vector>

#include "meshsal/meshsal.h"

namespace meshsal {
namespace detail {

class AttributeCarrier {
 public:
  // The input's attributes, per internal vertex (`order`: internal id -> input id).
  void take(const Mesh& mesh, const std::vector<uint32_t>& order);
  bool empty() const { return per_vertex_ == 0; }
  // b collapses into a, which moves from pa to np (b was at pb): a's values become linear
  // along the edge, at np's projection onto it.
  void carry(uint32_t a, uint32_t b, const double pa[3], const double pb[3], const double np[3]);
  // The attributes of the output vertices (`origin`: output -> input vertex; `inv`: input
  // -> internal). `moved`: per internal vertex, whether a collapse ever moved it (a normal
  // that never moved stays the input's exact one).
  void write(const Mesh& in, const std::vector<uint32_t>& origin, const std::vector<uint32_t>& inv,
             const std::vector<uint32_t>& moved, Mesh* out) const;

 private:
  size_t per_vertex_ = 0;           // attributes per vertex
  std::vector<float> values_;       // per_vertex_ per internal vertex
  int normal_at_[3] = {-1, -1, -1}; // which attributes are nx ny nz (-1: none)
};

}  // namespace detail
}  // namespace meshsal
