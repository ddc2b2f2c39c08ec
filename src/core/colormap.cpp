#include "core/colormap.h"

#include <algorithm>
#include <cmath>

namespace meshsal {

// Turbo (Mikhailov 2019, Google; Apache-2.0 polynomial fit): perceptually smooth, blue -> red.
void colormap_rgb(double t, uint8_t rgb[3]) {
  if (!std::isfinite(t)) t = 0;
  t = std::clamp(t, 0.0, 1.0);
  const double r = 0.13572138 + t * (4.61539260 + t * (-42.66032258 + t * (132.13108234 + t * (-152.94239396 + t * 59.28637943))));
  const double g = 0.09140261 + t * (2.19418839 + t * (4.84296658 + t * (-14.18503333 + t * (4.27729857 + t * 2.82956604))));
  const double b = 0.10667330 + t * (12.64194608 + t * (-60.58204836 + t * (110.36276771 + t * (-89.90310912 + t * 27.34824973))));
  const double c[3] = {r, g, b};
  for (int k = 0; k < 3; ++k) rgb[k] = uint8_t(std::lround(std::clamp(c[k], 0.0, 1.0) * 255.0));
}

std::vector<uint8_t> colormap_values(const std::vector<double>& values,
                                     const std::vector<uint8_t>& mask) {
  double lo = INFINITY, hi = -INFINITY;
  for (size_t v = 0; v < values.size(); ++v)
    if ((mask.empty() || mask[v]) && std::isfinite(values[v])) {
      lo = std::min(lo, values[v]);
      hi = std::max(hi, values[v]);
    }
  std::vector<uint8_t> rgb(3 * values.size());
  const double span = hi > lo ? hi - lo : 1.0;
  for (size_t v = 0; v < values.size(); ++v) {
    double t = (mask.empty() || mask[v]) && std::isfinite(lo) ? (values[v] - lo) / span : 0.0;
    colormap_rgb(t, &rgb[3 * v]);
  }
  return rgb;
}

}  // namespace meshsal
