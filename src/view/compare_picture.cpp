#include "view/compare_picture.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/mesh_points.h"
#include "core/model_frame.h"
#include "io/png_image.h"
#include "core/surface_distance.h"
#include "view/legend.h"
#include "view/picture.h"
#include "view/render.h"
#include "view/text.h"

namespace meshsal {

std::vector<double> distance_to(const Mesh& mesh, const Mesh& original) {
  TriangleBvh bvh = build_triangle_bvh(original);
  std::vector<uint8_t> is_point = referenced_vertices(mesh);
  std::vector<double> d(mesh.vertex_count(), 0.0);
  for (size_t v = 0; v < d.size(); ++v)
    if (is_point[v]) {
      double p[3] = {mesh.positions[3 * v], mesh.positions[3 * v + 1], mesh.positions[3 * v + 2]};
      d[v] = surface_distance(bvh, p);
    }
  return d;
}

Image compare_picture(const Mesh& original, const std::vector<double>* saliency, const Mesh& plain_in,
                      const Mesh& salient_in, const ViewAngles& view, const RenderStyle& style,
                      const std::string& title, const std::string& plain_name, const std::string& salient_name) {
  static const uint8_t kInk[3] = {20, 20, 20};
  // Meshes read from separate files have their own origins: all three in the original's.
  const Mesh plain = in_frame(plain_in, original.origin), salient = in_frame(salient_in, original.origin);
  const ViewFrame frame = frame_mesh(original, style.up);
  const PictureFit fit = fit_picture(original, frame, view);
  const double diag_pct = 100.0 / (2 * frame.radius);  // distances in % of the bbox diagonal
  const Mesh* meshes[3] = {&original, &plain, &salient};
  const std::string names[3] = {"original", plain_name, salient_name};

  // Colours: saliency on the original, distance (in % of the diagonal) on the others.
  ColorLimits sal_limits;
  std::vector<uint8_t> colours[3];
  if (saliency) colours[0] = score_colours(original, *saliency, style.range, &sal_limits);
  std::vector<double> dist[3];
  double dmax = 0;
  for (int i = 1; i < 3; ++i) {
    dist[i] = distance_to(*meshes[i], original);
    for (double& d : dist[i]) d *= diag_pct;
    for (double d : dist[i]) dmax = std::max(dmax, d);
  }
  const ColorLimits dist_limits{0.0, dmax > 0 ? dmax : 1.0};
  for (int i = 1; i < 3; ++i) colours[i] = colormap_values(dist[i], referenced_vertices(*meshes[i]), dist_limits);

  // Each panel: its name and faces, then (simplified ones) the numbers `meshsal compare`
  // prints for it, in % of the original's bounding-box diagonal.
  std::vector<std::string> lines[3];
  for (int i = 0; i < 3; ++i) lines[i].push_back(names[i] + ": " + std::to_string(meshes[i]->triangle_count()) + " faces");
  lines[0].push_back(saliency ? "coloured by saliency" : "");
  lines[0].push_back("");
  for (int i = 1; i < 3; ++i) {
    const SurfaceComparison c = compare_surfaces(original, *meshes[i], saliency ? *saliency : std::vector<double>{});
    const double pct = c.diagonal > 0 ? 100.0 / c.diagonal : 0.0;
    // 3 digits; below 1e-7 % of the diagonal it is rounding noise (a panel of the original itself).
    auto percent = [](double v) {
      char b[32];
      std::snprintf(b, sizeof b, "%.3g%%", v < 1e-7 ? 0.0 : v);
      return std::string(b);
    };
    lines[i].push_back("RMS " + percent(c.rms * pct) + ", Hausdorff " + percent(c.hausdorff * pct));
    lines[i].push_back(saliency ? "salient-region error " + percent(c.salient_error * pct) : "");
  }

  const int gap = 4, size = style.size;
  const int width = 3 * size + 2 * gap;
  const double px = text_size_for(size);
  const int pad = int(std::lround(px * 0.4)), line = int(std::lround(px * 1.25));
  const int title_h = pad + line * 4;
  const int bar_h = colour_bar_height(px) + 2 * pad;
  Image out(width, title_h + size + bar_h);
  draw_text(out, pad, pad, title + "   " + view_text(view, style.up), px, kInk);
  for (int i = 0; i < 3; ++i) {
    const int x0 = i * (size + gap);
    for (size_t k = 0; k < lines[i].size(); ++k)
      draw_text(out, x0 + pad, pad + line * int(k + 1), fit_text(lines[i][k], px, size - 2 * pad), px, kInk);
    RenderStyle panel = style;
    if (i == 0) panel.edges = false;  // the dense original would show only scattered edges
    blit(out, render_mesh(*meshes[i], i == 0 && !saliency ? nullptr : &colours[i], frame, view, panel, &fit), x0,
         title_h);
  }
  const int bar_y = title_h + size + pad;
  if (saliency) draw_colour_bar(out, 2 * pad, bar_y, size - 4 * pad, sal_limits, "saliency", px);
  draw_colour_bar(out, size + gap + 2 * pad, bar_y, 2 * size + gap - 4 * pad, dist_limits,
                  "distance to the original (% of the diagonal)", px);
  return out;
}

}  // namespace meshsal
