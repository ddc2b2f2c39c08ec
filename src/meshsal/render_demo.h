// meshsal: the pictures `meshsal demo` ends with.
#pragma once
#include <string>
#include <vector>

#include "meshsal/mesh.h"

namespace meshsal {

// Writes into `dir` (which must exist):
//   demo_best_view.png  the mesh coloured by saliency from its best view (gradient ascent,
//                       8 restarts, seed 1, CPU twin at 256 px)
//   demo_view_map.png   U over 2000 Fibonacci directions (equirectangular; ring: exhaustive
//                       maximum, cross: optimiser result)
//   demo_compare.png    original | plain | saliency-simplified from the best view, flat
//                       shaded with triangle edges (only when both simplified meshes are given)
// Returns the paths written. Throws Error.
std::vector<std::string> write_demo_pictures(const Mesh& mesh, const std::vector<double>& saliency,
                                             const std::string& dir, const Mesh* plain = nullptr,
                                             const Mesh* salient = nullptr);

}  // namespace meshsal
