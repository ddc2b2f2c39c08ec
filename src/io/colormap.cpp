#include "io/colormap.h"

#include "core/kth_smallest.h"
#include "core/parallel.h"
#include "core/parallel_select.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>

namespace meshsal {

// Turbo (Mikhailov 2019, Google; Apache-2.0 polynomial fit): perceptually smooth, blue -> red.
static void turbo(double t, uint8_t rgb[3]) {
  const double r = 0.13572138 + t * (4.61539260 + t * (-42.66032258 + t * (132.13108234 + t * (-152.94239396 + t * 59.28637943))));
  const double g = 0.09140261 + t * (2.19418839 + t * (4.84296658 + t * (-14.18503333 + t * (4.27729857 + t * 2.82956604))));
  const double b = 0.10667330 + t * (12.64194608 + t * (-60.58204836 + t * (110.36276771 + t * (-89.90310912 + t * 27.34824973))));
  const double c[3] = {r, g, b};
  for (int k = 0; k < 3; ++k) rgb[k] = uint8_t(std::lround(std::clamp(c[k], 0.0, 1.0) * 255.0));
}

void colormap_rgb(double t, uint8_t rgb[3]) {
  if (!std::isfinite(t)) t = 0;
  turbo(0.1 + 0.85 * std::clamp(t, 0.0, 1.0), rgb);
}

ColorLimits colour_limits(const std::vector<double>& values, const std::vector<uint8_t>& mask,
                          const ColorRange& range) {
  std::vector<double> vals;
  parallel_select(
      values.size(), 0, [&](size_t v) { return (mask.empty() || mask[v]) && std::isfinite(values[v]); },
      [&](size_t v) { return values[v]; }, vals);
  auto resolve = [&](double x, bool percentile) {
    if (!percentile) return x;
    if (vals.empty()) return 0.0;
    size_t k = size_t(std::lround(std::clamp(x, 0.0, 100.0) / 100.0 * double(vals.size() - 1)));
    return kth_smallest(vals, {k})[0];
  };
  ColorLimits l{resolve(range.lo, range.lo_percentile), resolve(range.hi, range.hi_percentile)};
  if (!(l.hi > l.lo)) l.hi = l.lo + 1;
  return l;
}

double colour_position(double v, const ColorLimits& limits) {
  const double t = (v - limits.lo) / (limits.hi - limits.lo);
  return std::isfinite(t) ? std::sqrt(std::clamp(t, 0.0, 1.0)) : 0.0;
}

std::vector<uint8_t> colormap_values(const std::vector<double>& values, const std::vector<uint8_t>& mask,
                                     const ColorLimits& limits) {
  std::vector<uint8_t> rgb(3 * values.size());
  parallel_for(values.size(), 0, 1 << 16, [&](size_t begin, size_t end) {
    for (size_t v = begin; v < end; ++v)
      colormap_rgb((mask.empty() || mask[v]) ? colour_position(values[v], limits) : 0.0, &rgb[3 * v]);
  });
  return rgb;
}

std::vector<uint8_t> colormap_values(const std::vector<double>& values, const std::vector<uint8_t>& mask,
                                     const ColorRange& range) {
  return colormap_values(values, mask, colour_limits(values, mask, range));
}

ColorRange parse_color_range(const std::string& text) {
  const std::string what = "color range must be LO,HI (numbers, or percentiles such as 5%,99%)";
  size_t comma = text.find(',');
  if (comma == std::string::npos || text.find(',', comma + 1) != std::string::npos)
    throw Error(what + ", got '" + text + "'");
  double v[2];
  bool pct[2];
  std::string part[2] = {text.substr(0, comma), text.substr(comma + 1)};
  for (int i = 0; i < 2; ++i) {
    std::string p = part[i];
    pct[i] = !p.empty() && p.back() == '%';
    if (pct[i]) p.pop_back();
    char* end = nullptr;
    errno = 0;
    v[i] = std::strtod(p.c_str(), &end);
    if (p.empty() || !end || *end != '\0' || errno == ERANGE || !std::isfinite(v[i]))
      throw Error(what + ", got '" + text + "'");
    if (pct[i] && (v[i] < 0 || v[i] > 100))
      throw Error("color range: a percentile must be in [0, 100], got '" + part[i] + "'");
  }
  if (pct[0] == pct[1] && !(v[0] < v[1]))
    throw Error("color range: LO must be below HI, got '" + text + "'");
  ColorRange r;
  r.lo = v[0];
  r.hi = v[1];
  r.lo_percentile = pct[0];
  r.hi_percentile = pct[1];
  return r;
}

}  // namespace meshsal
