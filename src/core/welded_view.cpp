// meshsal: position-welded view of a seam-split mesh (welded_view.h).
#include "core/welded_view.h"

#include <string>

namespace meshsal {

void check_position_vertex(const Mesh& mesh) {
  const std::vector<uint32_t>& pv = mesh.position_vertex;
  if (pv.empty()) return;
  const size_t n = mesh.vertex_count();
  if (pv.size() != n)
    throw Error("position_vertex has " + std::to_string(pv.size()) + " entries for " +
                std::to_string(n) + " vertices");
  for (size_t i = 0; i < n; ++i) {
    const uint32_t r = pv[i];
    if (r > i || pv[r] != r)
      throw Error("position_vertex of vertex " + std::to_string(i) +
                  " is not a lower vertex that stands for itself");
    for (int k = 0; k < 3; ++k)
      if (mesh.positions[3 * i + k] != mesh.positions[3 * size_t(r) + k])
        throw Error("vertex " + std::to_string(i) + " is not at the position of its position_vertex " +
                    std::to_string(r));
  }
}

Mesh position_welded(const Mesh& mesh) {
  Mesh out;
  out.positions = mesh.positions;
  out.triangles = mesh.triangles;
  const std::vector<uint32_t>& pv = mesh.position_vertex;
  if (!pv.empty())
    for (uint32_t& v : out.triangles)
      if (v < pv.size()) v = pv[v];
  return out;
}

}  // namespace meshsal
