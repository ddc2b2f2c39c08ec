// best_viewpoint(): the scorer for the chosen backend, gradient ascent, and the optional
// exhaustive map, as `meshsal viewpoint` runs them.
#include "api/viewpoint_backend.h"
#include "meshsal/meshsal.h"
#include "view/viewpoint.h"
#include "core/cancel.h"

namespace meshsal {

BestView best_viewpoint(const Mesh& mesh, const std::vector<double>& score,
                        const OptimiserOptions& options, int views,
                        const VisibilityOptions& visibility, Backend backend, int device) {
  const CancelScope cancel(options.cancel);
  if (views < 0) throw Error("views must be >= 0, got " + std::to_string(views));
  ViewScorerSetup setup = make_view_scorer(mesh, score, visibility, backend, device);
  BestView out;
  out.backend_name = setup.backend_name;
  out.optimised = optimise_viewpoint(setup.scorer, options);
  if (views > 0) out.map = exhaustive_map(setup.scorer, views, setup.batch, options.progress);
  return out;
}

}  // namespace meshsal
