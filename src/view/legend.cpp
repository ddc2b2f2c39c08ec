#include "view/legend.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "io/png_image.h"
#include "view/text.h"

namespace meshsal {

static const uint8_t kInk[3] = {20, 20, 20};

double text_size_for(int width) { return std::clamp(width / 32.0, 13.0, 28.0); }

int colour_bar_height(double px) { return int(std::ceil(px * 1.2 + px * 0.9 + 4 + px * 1.25 + px * 0.4)); }

std::string value_text(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", std::fabs(v) < 1e-12 ? 0.0 : v);
  return buf;
}

int colour_bar_x(int x, int w, const ColorLimits& l, double v) {
  return x + int(std::lround(colour_position(v, l) * (w - 1)));
}

void draw_colour_bar(Image& img, int x, int y, int w, const ColorLimits& l, const std::string& label, double px) {
  // Every picture places values at sqrt((v - lo) / (hi - lo)) (ColorRange): the bar says so.
  const std::string scaled = label + (label.empty() ? "" : ", ") + "square-root scale";
  draw_text(img, x, y, fit_text(text_width(scaled, px) <= w ? scaled : label, px, w), px, kInk);
  const int bar_y = y + int(std::lround(px * 1.2)), bar_h = int(std::lround(px * 0.9));
  for (int c = 0; c < w; ++c) {
    uint8_t rgb[3];
    colormap_rgb(w > 1 ? double(c) / (w - 1) : 0.0, rgb);
    for (int r = 0; r < bar_h; ++r)
      if (x + c >= 0 && x + c < img.width && bar_y + r < img.height) std::copy(rgb, rgb + 3, img.at(x + c, bar_y + r));
  }
  // Five ticks with their values; the end labels stay inside the bar's span, an inner label
  // that would touch a neighbour is left out (the tick stays).
  const int tick_y = bar_y + bar_h;
  int left_of[5], right_of[5];
  std::string texts[5];
  for (int i = 0; i <= 4; ++i) {
    const double v = l.lo + (l.hi - l.lo) * i / 4.0;
    const int tx = colour_bar_x(x, w, l, v);
    for (int r = 0; r < 4; ++r)
      if (tx >= 0 && tx < img.width && tick_y + r < img.height) std::copy(kInk, kInk + 3, img.at(tx, tick_y + r));
    texts[i] = value_text(v);
    const int tw = text_width(texts[i], px);
    left_of[i] = std::clamp(tx - tw / 2, x, x + w - tw);
    right_of[i] = left_of[i] + tw;
  }
  const int space = int(px * 0.6);
  int drawn_right = right_of[0];
  draw_text(img, left_of[0], tick_y + 4, texts[0], px, kInk);
  draw_text(img, left_of[4], tick_y + 4, texts[4], px, kInk);
  for (int i = 1; i <= 3; ++i)
    if (left_of[i] >= drawn_right + space && right_of[i] + space <= left_of[4]) {
      draw_text(img, left_of[i], tick_y + 4, texts[i], px, kInk);
      drawn_right = right_of[i];
    }
}

int title_height(double px, int lines) {
  return lines == 0 ? 0 : int(std::lround(px * 0.4)) + int(std::lround(px * 1.25)) * lines;
}

Image add_title_and_bar(const Image& body, const std::vector<std::string>& title, const ColorLimits* bar,
                        const std::string& bar_label) {
  const double px = text_size_for(body.width);
  const int pad = int(std::lround(px * 0.4)), line = int(std::lround(px * 1.25));
  int width = body.width;
  for (const std::string& t : title) width = std::max(width, text_width(t, px) + 2 * pad);
  const int title_h = title_height(px, int(title.size()));
  const int bar_h = bar ? colour_bar_height(px) + 2 * pad : 0;
  Image out(width, title_h + body.height + bar_h);
  for (size_t i = 0; i < title.size(); ++i) draw_text(out, pad, pad + line * int(i), title[i], px, kInk);
  blit(out, body, (width - body.width) / 2, title_h);
  if (bar) {
    const int bw = std::min(width - 4 * pad, std::max(200, width * 2 / 3));
    draw_colour_bar(out, (width - bw) / 2, title_h + body.height + pad, bw, *bar, bar_label, px);
  }
  return out;
}

}  // namespace meshsal
