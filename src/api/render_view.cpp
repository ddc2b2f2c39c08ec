#include "meshsal/meshsal.h"
#include "view/camera.h"
#include "view/render.h"

namespace meshsal {

Image render_view(const Mesh& mesh, const std::vector<double>& score, const ViewAngles& view,
                  const RenderStyle& style) {
  std::vector<uint8_t> colours;
  if (!score.empty()) colours = score_colours(mesh, score, style.range);
  return render_mesh(mesh, score.empty() ? nullptr : &colours, frame_mesh(mesh, style.up), view, style);
}

Image render_camera_view(const Mesh& mesh, const std::vector<double>& score, const ViewCamera& camera,
                         const RenderStyle& style) {
  RenderStyle s = style;
  s.up = camera.up_axis;
  return render_view(mesh, score, camera.view, s);
}

}  // namespace meshsal
