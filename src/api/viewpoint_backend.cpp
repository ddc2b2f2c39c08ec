#include "api/viewpoint_backend.h"

#include "meshsal/meshsal.h"
#include "api/gpu_backend.h"
#include "core/parallel.h"

namespace meshsal {

static ViewScorerSetup cpu_scorer(const Mesh& mesh, const std::vector<double>& score,
                                  const VisibilityOptions& options) {
  auto weights = std::make_shared<std::vector<float>>(visibility_weights(mesh, score));
  ViewFrame frame = frame_mesh(mesh);
  ViewScorerSetup s;
  s.keep_alive = weights;
  const Mesh* m = &mesh;
  s.scorer = [m, weights, frame, options](const std::vector<ViewAngles>& views) {
    return visible_score_cpu(*m, *weights, frame, views, options);
  };
  s.backend_name = "cpu (" + std::to_string(resolve_threads(options.threads)) + " threads)";
  s.batch = 64;
  return s;
}

ViewScorerSetup make_view_scorer(const Mesh& mesh, const std::vector<double>& score,
                                 const VisibilityOptions& options, Backend backend, int device,
                                 const std::function<void(const std::string&)>& notice, Device* session) {
  check_visibility_options(options);
  if (session) {
    if (backend == Backend::Cpu)
      throw Error("a Vulkan device session was given with the cpu backend: use backend gpu or auto, or no session");
    return gpu_backend().view_scorer_on(session_handle(*session), mesh, score, options);
  }
  if (backend == Backend::Gpu) return gpu_backend().view_scorer(mesh, score, options, device);
  if (backend == Backend::Auto) {
    int hw = -1;
    try {
      if (built_with_vulkan()) hw = pick_hardware_gpu(list_devices());
    } catch (const Error&) {
      hw = -1;  // no Vulkan driver at all
    }
    if (hw >= 0) return gpu_backend().view_scorer(mesh, score, options, device >= 0 ? device : hw);
    if (notice) notice("auto: no hardware GPU, visibility on the CPU twin (backend gpu uses any Vulkan device)");
  }
  return cpu_scorer(mesh, score, options);
}

}  // namespace meshsal
