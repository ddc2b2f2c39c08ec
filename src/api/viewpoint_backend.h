// meshsal: picks the visibility backend (GPU batch path or the CPU twin) for viewpoint search.
#pragma once
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "view/camera.h"
#include "meshsal/meshsal.h"
#include "saliency/saliency.h"
#include "view/viewpoint.h"
#include "view/visibility.h"
#include "api/gpu_backend.h"

namespace meshsal {

// Backend::Cpu: the CPU twin. Gpu: the Vulkan path (Error if unavailable). Auto: the GPU when
// a hardware GPU exists, else the CPU twin (notice() says so). With a session (the caller's
// open Device), Gpu and Auto score on it, `device` is not read (Cpu with one is an Error).
ViewScorerSetup make_view_scorer(const Mesh& mesh, const std::vector<double>& score,
                                 const VisibilityOptions& options, Backend backend, int device = -1,
                                 const std::function<void(const std::string&)>& notice = {},
                                 Device* session = nullptr);

}  // namespace meshsal
