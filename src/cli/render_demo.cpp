#include "cli/render_demo.h"

#include "view/render.h"
#include "view/viewpoint.h"
#include "api/viewpoint_backend.h"
#include "view/visibility.h"

namespace meshsal {

std::vector<std::string> write_demo_pictures(const Mesh& mesh, const std::vector<double>& saliency,
                                             const std::string& dir, const Mesh* plain,
                                             const Mesh* salient, const DemoPictureOptions& options) {
  ViewFrame frame = frame_mesh(mesh);
  VisibilityOptions vopt;
  vopt.resolution = options.resolution;
  ViewScorerSetup setup = make_view_scorer(mesh, saliency, vopt, options.backend);
  OptimiserResult best = optimise_viewpoint(setup.scorer, OptimiserOptions{});
  ViewMap map = exhaustive_map(setup.scorer, options.map_views, setup.batch);
  std::vector<uint8_t> colours = score_colours(mesh, saliency);
  std::string base = dir.empty() ? std::string(".") : dir;
  if (base.back() != '/') base += '/';
  std::vector<std::string> written;
  RenderStyle style;
  style.size = options.image_size;
  written.push_back(base + "demo_best_view.png");
  write_png(written.back(), render_mesh(mesh, &colours, frame, best.best, style));
  written.push_back(base + "demo_view_map.png");
  write_png(written.back(), render_view_map(map, 720, &map.views[map.best], &best.best));
  if (plain && salient) {
    style.smooth = false;
    style.edges = true;
    written.push_back(base + "demo_compare.png");
    write_png(written.back(), render_side_by_side({&mesh, plain, salient}, {&colours, nullptr, nullptr},
                                                  frame, best.best, style));
  }
  return written;
}

}  // namespace meshsal
