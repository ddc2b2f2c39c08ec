#include "view/map_picture.h"

#include <algorithm>
#include <cmath>

#include "io/png_image.h"
#include "view/legend.h"
#include "view/render.h"
#include "view/text.h"

namespace meshsal {

static const uint8_t kInk[3] = {20, 20, 20};

static void fill(Image& img, int x0, int y0, int w, int h, const uint8_t rgb[3]) {
  for (int y = std::max(0, y0); y < std::min(img.height, y0 + h); ++y)
    for (int x = std::max(0, x0); x < std::min(img.width, x0 + w); ++x) std::copy(rgb, rgb + 3, img.at(x, y));
}

Image view_map_picture(const ViewMap& map, int width, const ViewAngles& ring, const std::string& ring_label,
                       const ViewAngles& cross, const std::string& cross_label, const std::string& title) {
  const Image plot = render_view_map(map, width, &ring, &cross);
  const double px = text_size_for(std::max(width, 480));
  const int pad = int(std::lround(px * 0.4)), line = int(std::lround(px * 1.25));
  const int left = text_width("-90°", px) + text_width("phi", px) + 3 * pad + 6;
  const int top = title_height(px, 1) + pad;
  const int axis_h = 6 + line + line;  // ticks, their values, the axis name
  const int legend_h = 2 * (line + pad);  // one marker per line
  const int bar_h = colour_bar_height(px) + 2 * pad;
  const int right = 2 * pad + text_width("180°", px) / 2;
  Image out(left + plot.width + right, top + plot.height + axis_h + legend_h + bar_h);
  draw_text(out, pad, pad, title, px, kInk);
  blit(out, plot, left, top);
  // phi ticks on the left, theta ticks below, every 30 and 60 degrees.
  for (int phi = 90; phi >= -90; phi -= 30) {
    int x, y;
    view_map_pixel({0, phi * 3.14159265358979323846 / 180}, plot.width, &x, &y);
    y = phi == 90 ? 0 : phi == -90 ? plot.height - 1 : y;
    fill(out, left - 6, top + y, 6, 1, kInk);
    const std::string s = std::to_string(phi) + "°";
    draw_text(out, left - 8 - text_width(s, px), top + y - int(px * 0.6), s, px, kInk);
  }
  draw_text(out, pad, top + plot.height / 2 - int(px * 0.6), "phi", px, kInk);
  for (int theta = -180; theta <= 180; theta += 60) {
    const int x = theta == 180 ? plot.width - 1 : int(std::lround((theta + 180) / 360.0 * plot.width));
    fill(out, left + x, top + plot.height, 1, 6, kInk);
    const std::string s = std::to_string(theta) + "°";
    draw_text(out, left + x - text_width(s, px) / 2, top + plot.height + 6, s, px, kInk);
  }
  const std::string theta_name = "theta";
  draw_text(out, left + plot.width / 2 - text_width(theta_name, px) / 2, top + plot.height + 6 + line, theta_name,
            px, kInk);
  // Legend: the markers as render_view_map draws them, then their labels.
  const int ly = top + plot.height + axis_h, r = int(px * 0.4);
  int lx = left;
  {
    Image sample(2 * r + 8, 2 * r + 8, 120, 120, 120);  // the markers on mid grey
    const int cx = r + 4, cy = r + 4;
    for (int dy = -r - 2; dy <= r + 2; ++dy)
      for (int dx = -r - 2; dx <= r + 2; ++dx) {
        double dd = std::sqrt(double(dx * dx + dy * dy));
        uint8_t* p = sample.at(cx + dx, cy + dy);
        if (std::fabs(dd - r) < 0.8) p[0] = p[1] = p[2] = 255;
        else if (std::fabs(dd - r) < 1.8) p[0] = p[1] = p[2] = 0;
      }
    blit(out, sample, lx, ly);
    lx += sample.width + pad;
    draw_text(out, lx, ly + (sample.height - line) / 2, ring_label, px, kInk);
    Image cs(2 * r + 8, 2 * r + 8, 120, 120, 120);
    for (int k = -r; k <= r; ++k)
      for (int w = -2; w <= 1; ++w) {
        uint8_t v = (w == -1 || w == 0) ? 0 : 255;
        uint8_t* a = cs.at(cx + k, cy + w);
        uint8_t* b = cs.at(cx + w, cy + k);
        if (v == 0 || a[0] != 0) a[0] = a[1] = a[2] = v;
        if (v == 0 || b[0] != 0) b[0] = b[1] = b[2] = v;
      }
    lx = left;
    const int ly2 = ly + line + pad;
    blit(out, cs, lx, ly2);
    lx += cs.width + pad;
    draw_text(out, lx, ly2 + (cs.height - line) / 2, cross_label, px, kInk);
  }
  ColorLimits l{*std::min_element(map.U.begin(), map.U.end()), *std::max_element(map.U.begin(), map.U.end())};
  if (!(l.hi > l.lo)) l.hi = l.lo + 1;
  draw_colour_bar(out, left, ly + legend_h + pad, plot.width, l,
                  "visible score U of the view from (theta, phi), smoothed", px);
  return out;
}

}  // namespace meshsal
