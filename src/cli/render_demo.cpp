#include "cli/render_demo.h"

#include "view/compare_picture.h"
#include "view/legend.h"
#include "view/map_picture.h"
#include "view/picture.h"
#include "view/render.h"

namespace meshsal {

std::vector<std::string> write_demo_pictures(const Mesh& mesh, const std::vector<double>& saliency,
                                             const std::string& dir, const Mesh* plain,
                                             const Mesh* salient, const DemoPictureOptions& options) {
  // The one view pipeline (best_viewpoint), at the demo's own z-buffer size.
  ViewpointOptions vo;
  vo.visibility.resolution = options.resolution;
  vo.views = options.map_views;
  vo.backend = options.backend;
  const Viewpoint v = best_viewpoint(mesh, saliency, vo);
  const OptimiserResult& best = v.optimised;
  const ViewMap& map = v.map;
  std::string base = dir.empty() ? std::string(".") : dir;
  if (base.back() != '/') base += '/';
  std::vector<std::string> written;
  RenderStyle style;
  style.size = options.image_size;
  const std::string name = "bumpy sphere";
  written.push_back(base + "demo_best_view.png");
  write_png(written.back(), titled_view(mesh, &saliency, best.best, style, name, "saliency"));
  written.push_back(base + "demo_view_map.png");
  write_png(written.back(),
            view_map_picture(map, 720, map.views[map.best],
                             "exhaustive maximum (" + std::to_string(options.map_views) + " views), U = " +
                                 value_text(map.U[map.best]),
                             best.best, "optimiser's result, U = " + value_text(best.U),
                             name + ": visible saliency by view direction"));
  if (plain && salient) {
    style.smooth = false;
    style.edges = true;
    written.push_back(base + "demo_compare.png");
    write_png(written.back(), compare_picture(mesh, &saliency, *plain, *salient, best.best, style, name));
  }
  return written;
}

}  // namespace meshsal
