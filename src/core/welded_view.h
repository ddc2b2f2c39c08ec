// meshsal: the position-welded view of a mesh whose vertices are split at attribute seams
// (Mesh::position_vertex): what curvature and saliency see, so that a seam does not cut
// the surface, and the copy of per-vertex results back onto the split twins.
#pragma once
#include <cstdint>
#include <vector>

#include "meshsal/meshsal.h"

namespace meshsal {

// Throws Error unless position_vertex is empty or holds, for every vertex, a vertex at or
// below it that maps to itself and has the same position.
void check_position_vertex(const Mesh& mesh);

// The same positions, every triangle corner replaced by its position_vertex; no
// attributes, no position_vertex. The twins are left unreferenced (not mesh points).
Mesh position_welded(const Mesh& mesh);

// values[i] = values[position_vertex[i]] for every twin (no-op when there are none).
template <class T>
void copy_to_twins(const Mesh& mesh, std::vector<T>& values) {
  const std::vector<uint32_t>& pv = mesh.position_vertex;
  if (pv.empty() || values.size() != pv.size()) return;
  for (size_t i = 0; i < pv.size(); ++i)
    if (pv[i] != i) values[i] = values[pv[i]];
}

}  // namespace meshsal
