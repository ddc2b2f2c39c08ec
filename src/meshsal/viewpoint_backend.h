// meshsal: picks the visibility backend (GPU batch path or the CPU twin) for viewpoint search.
#pragma once
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "meshsal/camera.h"
#include "meshsal/mesh.h"
#include "meshsal/saliency.h"
#include "meshsal/viewpoint.h"
#include "meshsal/visibility.h"

namespace meshsal {

struct ViewScorerSetup {
  ViewScorer scorer;
  std::string backend_name;          // "cpu (N threads)" or "vulkan: <device>"
  int batch = 64;                    // good batch size for exhaustive maps
  std::shared_ptr<void> keep_alive;  // owns the GPU state the scorer uses
};

// Backend::Cpu: the CPU twin. Gpu: the Vulkan path (Error if unavailable). Auto: the GPU when
// a hardware GPU exists, else the CPU twin (notice() says so).
ViewScorerSetup make_view_scorer(const Mesh& mesh, const std::vector<double>& score,
                                 const VisibilityOptions& options, Backend backend, int device = -1,
                                 const std::function<void(const std::string&)>& notice = {});

}  // namespace meshsal
