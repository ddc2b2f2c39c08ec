// meshsal (internal to api/): Method::Auto decided for a mesh, where the backend switch
// (saliency_backend.cpp) chooses the path.
#pragma once
#include "meshsal/meshsal.h"

namespace meshsal {

// options.method with Auto decided for this mesh (Fast when the exact sweep's estimated
// pairs pass kAutoPairBudget, with a notice); compute_saliency and smooth_saliency use it.
Method resolve_method(const Mesh& mesh, const SaliencyOptions& options);

// For options.method Exact on the CPU (method resolved): a one-line note when the sweep's
// estimated pairs (as Auto estimates them) mean more than a minute at the measured CPU
// rate on options.threads, naming its cost and --method fast; "" otherwise. The CPU
// paths of compute_saliency give it to options.notice before they start.
std::string long_sweep_note(const Mesh& mesh, const SaliencyOptions& options);

}  // namespace meshsal
