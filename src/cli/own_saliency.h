// meshsal CLI: a saliency PLY given as the input mesh brings its own saliency.
#pragma once
#include <string>

#include "meshsal/meshsal.h"

namespace meshsal_cli {

// The file `render` and `viewpoint` should read the saliency from: --saliency-from when
// given; else the input itself when it has a per-vertex `quality` (a PLY that `meshsal
// saliency` wrote), saying so on stderr; else "" (compute it). Only for the saliency score.
std::string saliency_source_file(const std::string& input, const meshsal::VertexProperties& props,
                                 const std::string& saliency_from, bool saliency_score);

}  // namespace meshsal_cli
