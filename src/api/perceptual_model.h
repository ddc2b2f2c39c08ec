// meshsal (internal to api/): the models of S other than the paper's (Model, meshsal/saliency.h):
// the perceptual model and its cues alone. compute_saliency calls it for them.
#pragma once
#include "meshsal/meshsal.h"

namespace meshsal {

// S of options.model (not Lee2005) for a mesh without seam twins, options checked.
SaliencyResult compute_model_saliency(const Mesh& mesh, const SaliencyOptions& options);

}  // namespace meshsal
