#include "meshsal/viewpoint_backend.h"

#include "meshsal/error.h"
#include "meshsal/parallel.h"

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
                                 const VisibilityOptions& options, Backend backend, int /*device*/,
                                 const std::function<void(const std::string&)>& notice) {
  check_visibility_options(options);
  if (backend == Backend::Gpu) throw Error("the GPU visibility path is not available in this build");
  if (backend == Backend::Auto && notice) notice("auto: no GPU visibility path, using the CPU twin");
  return cpu_scorer(mesh, score, options);
}

}  // namespace meshsal
