#include "view/tradeoff_plot.h"

#include <algorithm>
#include <cmath>

#include "view/legend.h"
#include "view/text.h"

namespace meshsal {

namespace {

const uint8_t kInk[3] = {20, 20, 20};
const uint8_t kGrid[3] = {225, 225, 225};
const uint8_t kTargetShade[3] = {226, 244, 226};
constexpr double kTextPx = 14;

enum class Marker { Dot, Square, Diamond, Triangle, Cross };

Marker series_marker(int s) {
  switch (s) {
    case kPaperRecipe: return Marker::Square;
    case kBalancedPreset: return Marker::Diamond;
    case kMeshoptimizer: return Marker::Triangle;
    default: return Marker::Dot;
  }
}

void put(Image& img, int x, int y, const uint8_t rgb[3]) {
  if (x >= 0 && y >= 0 && x < img.width && y < img.height) std::copy(rgb, rgb + 3, img.at(x, y));
}

void fill_rect(Image& img, int x0, int y0, int x1, int y1, const uint8_t rgb[3]) {
  for (int y = std::max(0, y0); y <= std::min(img.height - 1, y1); ++y)
    for (int x = std::max(0, x0); x <= std::min(img.width - 1, x1); ++x) put(img, x, y, rgb);
}

// Axis-parallel lines; dashed: 6 on, 4 off.
void hline(Image& img, int x0, int x1, int y, const uint8_t rgb[3], bool dashed = false) {
  for (int x = x0; x <= x1; ++x)
    if (!dashed || (x - x0) % 10 < 6) put(img, x, y, rgb);
}
void vline(Image& img, int x, int y0, int y1, const uint8_t rgb[3], bool dashed = false) {
  for (int y = y0; y <= y1; ++y)
    if (!dashed || (y - y0) % 10 < 6) put(img, x, y, rgb);
}

void draw_marker(Image& img, int cx, int cy, Marker m, const uint8_t rgb[3]) {
  switch (m) {
    case Marker::Dot:
      for (int dy = -2; dy <= 2; ++dy)
        for (int dx = -2; dx <= 2; ++dx)
          if (dx * dx + dy * dy <= 5) put(img, cx + dx, cy + dy, rgb);
      break;
    case Marker::Square:
      fill_rect(img, cx - 5, cy - 5, cx + 5, cy + 5, rgb);
      break;
    case Marker::Diamond:
      for (int dy = -7; dy <= 7; ++dy)
        for (int dx = -7; dx <= 7; ++dx)
          if (std::abs(dx) + std::abs(dy) <= 7) put(img, cx + dx, cy + dy, rgb);
      break;
    case Marker::Triangle:
      for (int dy = -6; dy <= 6; ++dy)
        for (int dx = -7; dx <= 7; ++dx)
          if (2 * std::abs(dx) <= dy + 7) put(img, cx + dx, cy + dy, rgb);
      break;
    case Marker::Cross:
      for (int d = -6; d <= 6; ++d)
        for (int t = -1; t <= 1; ++t) put(img, cx + d, cy + d + t, rgb), put(img, cx + d, cy - d + t, rgb);
      break;
  }
}

// Tick step for about five ticks over `span`: 1, 2 or 5 times a power of ten.
double tick_step(double span) {
  const double raw = span / 5;
  const double p = std::pow(10.0, std::floor(std::log10(raw)));
  for (double m : {1.0, 2.0, 5.0})
    if (m * p >= raw) return m * p;
  return 10 * p;
}

struct Axis {
  double lo, hi;
  int p0, p1;  // pixel of lo and of hi
  int at(double v) const { return p0 + int(std::lround((v - lo) / (hi - lo) * (p1 - p0))); }
};

// A range over the values, 1 and the target, widened by 6% and snapped to the tick step.
Axis make_axis(std::vector<double> values, double target, int p0, int p1) {
  values.push_back(1);
  values.push_back(target);
  double lo = *std::min_element(values.begin(), values.end());
  double hi = *std::max_element(values.begin(), values.end());
  const double pad = 0.06 * (hi - lo);
  lo -= pad;
  hi += pad;
  const double step = tick_step(hi - lo);
  return {std::floor(lo / step) * step, std::ceil(hi / step) * step, p0, p1};
}

void draw_panel(Image& img, int ox, int oy, const TradeoffPanel& panel, TradeoffPoint target) {
  const int x0 = ox + kPlotLeft, x1 = ox + kPanelWidth - kPlotRight;
  const int y0 = oy + kPlotTop, y1 = oy + kPanelHeight - kPlotBottom;
  std::vector<double> xs, ys;
  for (const auto& s : panel.series)
    for (const TradeoffPoint& p : s)
      if (std::isfinite(p.x) && std::isfinite(p.y)) xs.push_back(p.x), ys.push_back(p.y);
  const Axis ax = make_axis(xs, target.x, x0, x1);
  const Axis ay = make_axis(ys, target.y, y1, y0);  // up is larger
  // The target region, the grid with tick values, then the frame.
  fill_rect(img, x0, std::max(y0, ay.at(target.y)), std::min(x1, ax.at(target.x)), y1, kTargetShade);
  const double sx = tick_step(ax.hi - ax.lo), sy = tick_step(ay.hi - ay.lo);
  for (double v = ax.lo; v <= ax.hi + 1e-9 * sx; v += sx) {
    const int x = ax.at(v);
    vline(img, x, y0, y1, kGrid);
    vline(img, x, y1, y1 + 4, kInk);
    const std::string t = value_text(v);
    draw_text(img, x - text_width(t, kTextPx) / 2, y1 + 6, t, kTextPx, kInk);
  }
  for (double v = ay.lo; v <= ay.hi + 1e-9 * sy; v += sy) {
    const int y = ay.at(v);
    hline(img, x0, x1, y, kGrid);
    hline(img, x0 - 4, x0, y, kInk);
    const std::string t = value_text(v);
    draw_text(img, x0 - 7 - text_width(t, kTextPx), y - int(kTextPx * 0.6), t, kTextPx, kInk);
  }
  // Plain quadrics' errors (1) and the targets as dashed lines.
  const uint8_t target_ink[3] = {40, 140, 40};
  vline(img, ax.at(target.x), y0, y1, target_ink, true);
  hline(img, x0, x1, ay.at(target.y), target_ink, true);
  hline(img, x0, x1, y0, kInk), hline(img, x0, x1, y1, kInk);
  vline(img, x0, y0, y1, kInk), vline(img, x1, y0, y1, kInk);
  draw_text(img, x0, oy + 6, panel.title, kTextPx, kInk);
  const std::string xl = "RMS error / plain";
  draw_text(img, (x0 + x1 - text_width(xl, kTextPx)) / 2, y1 + 8 + int(kTextPx * 1.2), xl, kTextPx, kInk);
  const std::string yl = "salient error / plain";
  draw_text(img, x1 - text_width(yl, kTextPx), oy + 6, yl, kTextPx, kInk);
  // Sweeps first, named methods over them; points outside the range are not drawn.
  auto inside = [&](int x, int y) { return x >= x0 && x <= x1 && y >= y0 && y <= y1; };
  for (int s = 0; s < kTradeoffSeriesCount; ++s) {
    uint8_t rgb[3];
    tradeoff_series_colour(s, rgb);
    for (const TradeoffPoint& p : panel.series[s]) {
      const int x = ax.at(p.x), y = ay.at(p.y);
      if (inside(x, y)) draw_marker(img, x, y, series_marker(s), rgb);
    }
  }
  if (inside(ax.at(1), ay.at(1))) draw_marker(img, ax.at(1), ay.at(1), Marker::Cross, kInk);
}

}  // namespace

const char* tradeoff_series_name(int series) {
  static const char* names[kTradeoffSeriesCount] = {
      "sweep: threshold (paper's curve)", "sweep: rank step/ramp", "sweep: continuous",
      "saliency (paper's recipe)", "balanced (preset)", "meshoptimizer"};
  return series >= 0 && series < kTradeoffSeriesCount ? names[series] : "?";
}

void tradeoff_series_colour(int series, uint8_t rgb[3]) {
  static const uint8_t colours[kTradeoffSeriesCount][3] = {
      {250, 150, 140}, {140, 170, 240}, {200, 160, 230}, {215, 25, 28}, {20, 150, 60}, {30, 80, 200}};
  const int s = std::clamp(series, 0, kTradeoffSeriesCount - 1);
  std::copy(colours[s], colours[s] + 3, rgb);
}

Image tradeoff_plot(const std::vector<TradeoffPanel>& panels, TradeoffPoint target) {
  if (panels.empty()) throw Error("tradeoff plot: no panels");
  const int cols = panels.size() > 1 ? 2 : 1;
  const int rows = int((panels.size() + cols - 1) / cols);
  const int legend_rows = (kTradeoffSeriesCount + 2 + 1) / 2;  // the series, plain, the target
  const int line = int(kTextPx * 1.6);
  const int legend_h = legend_rows * line + 16;
  Image img(cols * kPanelWidth, rows * kPanelHeight + legend_h);
  for (size_t i = 0; i < panels.size(); ++i)
    draw_panel(img, int(i % cols) * kPanelWidth, int(i / cols) * kPanelHeight, panels[i], target);
  // Legend: two columns of marker + name.
  const int ly = rows * kPanelHeight + 8;
  const int colw = img.width / 2;
  for (int k = 0; k < kTradeoffSeriesCount + 2; ++k) {
    const int x = 20 + (k % 2) * colw, y = ly + (k / 2) * line;
    const int cy = y + line / 2 - 2;
    std::string name;
    if (k < kTradeoffSeriesCount) {
      uint8_t rgb[3];
      tradeoff_series_colour(k, rgb);
      draw_marker(img, x + 8, cy, series_marker(k), rgb);
      name = tradeoff_series_name(k);
    } else if (k == kTradeoffSeriesCount) {
      draw_marker(img, x + 8, cy, Marker::Cross, kInk);
      name = "none (plain quadrics) = (1, 1)";
    } else {
      fill_rect(img, x, cy - 6, x + 16, cy + 6, kTargetShade);
      name = "target: salient <= " + value_text(target.y) + ", RMS <= " + value_text(target.x);
    }
    draw_text(img, x + 24, cy - int(kTextPx * 0.6), name, kTextPx, kInk);
  }
  return img;
}

}  // namespace meshsal
