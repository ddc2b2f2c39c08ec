#include "saliency/suppression.h"

namespace meshsal {

std::vector<double> suppress(const std::vector<double>& map, const std::vector<uint8_t>& is_point,
                             const Adjacency& adj, SuppressionInfo* info) {
  const size_t n = map.size();
  SuppressionInfo si;
  size_t global = n;  // lowest-index mesh point attaining the maximum
  for (size_t v = 0; v < n; ++v)
    if (is_point[v] && (global == n || map[v] > si.max)) {
      si.max = map[v];
      global = v;
    }
  std::vector<double> out(n, 0.0);
  if (!(si.max > 0)) {
    if (info) *info = si;
    return out;
  }
  for (size_t v = 0; v < n; ++v)
    if (is_point[v]) out[v] = map[v] / si.max;

  // Local maxima: strictly greater than every 1-ring neighbour. mbar averages those other
  // than the global maximum (which is 1 after normalisation).
  double sum = 0;
  size_t others = 0;
  for (size_t v = 0; v < n; ++v) {
    if (!is_point[v]) continue;
    bool is_max = true;
    for (uint32_t e = adj.offsets[v]; e < adj.offsets[v + 1] && is_max; ++e)
      is_max = out[v] > out[adj.neighbors[e]];
    if (!is_max) continue;
    si.local_maxima++;
    if (v == global) continue;
    sum += out[v];
    others++;
  }
  si.mbar = others > 0 ? sum / double(others) : 0.0;
  const double factor = (1.0 - si.mbar) * (1.0 - si.mbar);
  for (size_t v = 0; v < n; ++v) out[v] *= factor;
  if (info) *info = si;
  return out;
}

}  // namespace meshsal
