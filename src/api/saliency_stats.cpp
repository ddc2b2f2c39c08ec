// saliency_stats(): what every front end reports of S (meshsal/saliency.h).
#include <algorithm>
#include <cmath>
#include <vector>

#include "core/kth_smallest.h"
#include "core/parallel_select.h"
#include "meshsal/meshsal.h"

namespace meshsal {

SaliencyStats saliency_stats(const SaliencyResult& r) {
  std::vector<double> s;
  parallel_select(
      r.saliency.size(), 0, [&](size_t v) { return v < r.is_point.size() && r.is_point[v]; },
      [&](size_t v) { return r.saliency[v]; }, s);
  SaliencyStats st;
  st.points = s.size();
  if (s.empty()) return st;
  double sum = 0;  // in vertex order, as the out-of-core statistics add them
  for (double x : s) sum += x;
  auto rank = [&](double p) {
    const size_t k = static_cast<size_t>(std::ceil(p / 100.0 * double(s.size())));
    return std::min(s.size() - 1, k == 0 ? 0 : k - 1);
  };
  const std::vector<double> q = kth_smallest(s, {0, rank(10), rank(50), rank(90), rank(99), s.size() - 1});
  st.min = q[0];
  st.max = q[5];
  st.mean = sum / double(s.size());
  st.p10 = q[1];
  st.p50 = q[2];
  st.p90 = q[3];
  st.p99 = q[4];
  return st;
}

}  // namespace meshsal
