#include "saliency/perceptual_cues.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace meshsal {

std::vector<double> height_cue(const Mesh& mesh, const std::vector<uint8_t>& is_point, const double up[3]) {
  const size_t n = mesh.vertex_count();
  std::vector<double> h(n, 0.0);
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (size_t i = 0; i < n; ++i) {
    if (!is_point[i]) continue;
    const float* p = &mesh.positions[3 * i];
    h[i] = double(p[0]) * up[0] + double(p[1]) * up[1] + double(p[2]) * up[2];
    lo = std::min(lo, h[i]);
    hi = std::max(hi, h[i]);
  }
  for (size_t i = 0; i < n; ++i) h[i] = is_point[i] && hi > lo ? (h[i] - lo) / (hi - lo) : 0.0;
  return h;
}

std::vector<double> rarity_descriptor_scales() { return {2, 4, 8}; }

namespace {

// The value at quantile q of `v` (nearest rank; v is reordered).
double quantile(std::vector<double>& v, double q) {
  const size_t k = std::min(v.size() - 1, size_t(q * double(v.size() - 1) + 0.5));
  std::nth_element(v.begin(), v.begin() + ptrdiff_t(k), v.end());
  return v[k];
}

}  // namespace

std::vector<double> global_rarity(const std::vector<std::vector<double>>& columns, const std::vector<uint8_t>& is_point) {
  const size_t n = is_point.size();
  std::vector<double> info(n, 0.0);
  size_t points = 0;
  for (uint8_t p : is_point) points += p;
  if (points == 0 || columns.empty()) return info;
  std::vector<uint32_t> cell(n, 0);
  uint64_t stride = 1;
  std::vector<double> v;
  for (const std::vector<double>& col : columns) {
    if (col.size() != n) throw Error("rarity: a descriptor column does not match the mesh");
    v.clear();
    for (size_t i = 0; i < n; ++i)
      if (is_point[i]) v.push_back(col[i]);
    double lo = quantile(v, 0.005), hi = quantile(v, 0.995);
    if (!(hi > lo)) {
      lo = *std::min_element(v.begin(), v.end());
      hi = *std::max_element(v.begin(), v.end());
    }
    const double scale = hi > lo ? kRarityBins / (hi - lo) : 0;
    for (size_t i = 0; i < n; ++i) {
      if (!is_point[i]) continue;
      const double b = std::floor((col[i] - lo) * scale);
      const uint32_t bin = uint32_t(std::clamp(b, 0.0, double(kRarityBins - 1)));
      cell[i] += uint32_t(stride) * bin;
    }
    stride *= kRarityBins;
    if (stride > (uint64_t(1) << 24)) throw Error("rarity: too many descriptor dimensions");
  }
  std::vector<uint64_t> count(stride, 0);
  for (size_t i = 0; i < n; ++i)
    if (is_point[i]) ++count[cell[i]];
  for (size_t i = 0; i < n; ++i)
    if (is_point[i]) info[i] = std::log(double(points) / double(count[cell[i]]));
  return info;
}

void scale_to_max(std::vector<double>& values, const std::vector<uint8_t>& is_point) {
  double top = 0;
  for (size_t i = 0; i < values.size(); ++i)
    if (is_point[i]) top = std::max(top, values[i]);
  for (size_t i = 0; i < values.size(); ++i) values[i] = !is_point[i] ? 0.0 : top > 0 ? values[i] / top : values[i];
}

}  // namespace meshsal
