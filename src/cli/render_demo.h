// meshsal: the pictures `meshsal demo` ends with.
#pragma once
#include <string>
#include <vector>

#include "meshsal/meshsal.h"
#include "saliency/saliency.h"

namespace meshsal {

struct DemoPictureOptions {
  Backend backend = Backend::Auto;  // visibility: GPU when a hardware one exists, else CPU twin
  int resolution = 128;             // z-buffer side for the view search
  int map_views = 1000;             // Fibonacci directions of the view map
  int image_size = 512;             // side of each rendered panel
};

// Writes into `dir` (which must exist):
//   demo_best_view.png  the mesh coloured by saliency from its best view (gradient ascent,
//                       8 restarts, seed 1), titled, with its colour bar (titled_view)
//   demo_view_map.png   U over options.map_views Fibonacci directions (view_map_picture:
//                       axes, colour bar; ring: exhaustive maximum, cross: optimiser result)
//   demo_compare.png    original | plain | saliency-simplified from the best view, flat
//                       shaded with triangle edges, labelled, the simplified ones coloured by
//                       distance (compare_picture; only when both simplified meshes are given)
// Returns the paths written. Throws Error.
std::vector<std::string> write_demo_pictures(const Mesh& mesh, const std::vector<double>& saliency,
                                             const std::string& dir, const Mesh* plain = nullptr,
                                             const Mesh* salient = nullptr,
                                             const DemoPictureOptions& options = {});

}  // namespace meshsal
