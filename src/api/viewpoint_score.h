// meshsal: the per-vertex score that viewpoint selection and the pictures use.
#pragma once
#include <string>
#include <vector>

#include "meshsal/meshsal.h"
#include "saliency/saliency.h"

namespace meshsal {

enum class ViewScore { Saliency, Curvature };

// "saliency" or "curvature"; throws Error otherwise.
ViewScore parse_view_score(const std::string& text);

// Saliency S per vertex: the `quality` property of `saliency_from` (a PLY written by
// `meshsal saliency` for this mesh: load_saliency_ply) when given, else computed with
// `options`. Curvature: |H| (the paper's baseline), computed. Throws Error.
std::vector<double> vertex_score(const Mesh& mesh, ViewScore kind, const std::string& saliency_from,
                                 const SaliencyOptions& options, std::string* source = nullptr);

}  // namespace meshsal
