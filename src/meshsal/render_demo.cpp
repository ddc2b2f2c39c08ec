#include "meshsal/render_demo.h"

#include "meshsal/render.h"
#include "meshsal/viewpoint.h"
#include "meshsal/visibility.h"

namespace meshsal {

std::vector<std::string> write_demo_pictures(const Mesh& mesh, const std::vector<double>& saliency,
                                             const std::string& dir, const Mesh* plain,
                                             const Mesh* salient) {
  std::vector<float> weights = visibility_weights(mesh, saliency);
  ViewFrame frame = frame_mesh(mesh);
  VisibilityOptions vopt;
  vopt.resolution = 256;
  ViewScorer scorer = [&](const std::vector<ViewAngles>& views) {
    return visible_score_cpu(mesh, weights, frame, views, vopt);
  };
  OptimiserResult best = optimise_viewpoint(scorer, OptimiserOptions{});
  ViewMap map = exhaustive_map(scorer, 2000);
  std::vector<uint8_t> colours = score_colours(mesh, saliency);
  std::string base = dir.empty() ? std::string(".") : dir;
  if (base.back() != '/') base += '/';
  std::vector<std::string> written;
  RenderStyle style;
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
