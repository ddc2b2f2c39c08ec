#include "view/picture.h"

#include <cmath>
#include <cstdio>

#include "view/legend.h"
#include "view/render.h"
#include "view/visibility.h"

namespace meshsal {

static const char* up_name(UpAxis up) {
  switch (up) {
    case UpAxis::Y: return "y";
    case UpAxis::MinusY: return "-y";
    case UpAxis::Z: return "z";
    case UpAxis::MinusZ: return "-z";
    case UpAxis::X: return "x";
    case UpAxis::MinusX: return "-x";
  }
  return "y";
}

std::string view_text(const ViewAngles& view, UpAxis up) {
  const double deg = 180.0 / 3.14159265358979323846;
  char buf[96];
  std::snprintf(buf, sizeof buf, "theta %.1f°  phi %.1f°  (%s up)", view.theta * deg, view.phi * deg, up_name(up));
  return buf;
}

VisibleScore picture_visible_score(const Mesh& mesh, const std::vector<double>& score, const ViewAngles& view,
                                   UpAxis up) {
  const std::vector<float> weights = visibility_weights(mesh, score);
  VisibilityOptions vopt;
  vopt.resolution = 512;
  VisibleScore v;
  v.U = visible_score_cpu(mesh, weights, frame_mesh(mesh, up), {view}, vopt)[0];
  for (float w : weights) v.total += w;
  return v;
}

Image titled_view(const Mesh& mesh, const std::vector<double>* score, const ViewAngles& view,
                  const RenderStyle& style, const std::string& name, const std::string& score_name,
                  VisibleScore* shown) {
  const ViewFrame frame = frame_mesh(mesh, style.up);
  std::vector<std::string> title{name + "   " + view_text(view, style.up)};
  if (shown) *shown = {};
  if (!score) return add_title_and_bar(render_mesh(mesh, nullptr, frame, view, style), title, nullptr, "");
  ColorLimits limits;
  std::vector<uint8_t> colours = score_colours(mesh, *score, style.range, &limits);
  const VisibleScore v = picture_visible_score(mesh, *score, view, style.up);
  if (shown) *shown = v;
  char buf[160];
  std::snprintf(buf, sizeof buf, "visible %s U = %s (%.0f%% of the total)", score_name.c_str(),
                value_text(v.U).c_str(), v.total > 0 ? 100.0 * v.U / v.total : 0.0);
  title.push_back(buf);
  return add_title_and_bar(render_mesh(mesh, &colours, frame, view, style), title, &limits, score_name);
}

}  // namespace meshsal
