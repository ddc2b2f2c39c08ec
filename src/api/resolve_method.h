// meshsal (internal to api/): Method::Auto decided for a mesh, where the backend switch
// (saliency_backend.cpp) chooses the path.
#pragma once
#include "meshsal/meshsal.h"

namespace meshsal {

// options.method with Auto decided for this mesh (Fast when the exact sweep's estimated
// pairs pass kAutoPairBudget, with a notice); compute_saliency and smooth_saliency use it.
Method resolve_method(const Mesh& mesh, const SaliencyOptions& options);

}  // namespace meshsal
