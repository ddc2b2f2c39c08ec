#include "core/kth_smallest.h"

#include <algorithm>
#include <numeric>

#include "meshsal/meshsal.h"

namespace meshsal {

std::vector<double> kth_smallest(std::vector<double>& values, const std::vector<size_t>& ks) {
  std::vector<size_t> order(ks.size());
  std::iota(order.begin(), order.end(), size_t(0));
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return ks[a] < ks[b]; });
  std::vector<double> out(ks.size());
  // Ascending ks: each nth_element works on what lies above the previous one.
  size_t from = 0;
  for (size_t i : order) {
    const size_t k = ks[i];
    if (k >= values.size()) throw Error("internal: order statistic past the end");
    if (k >= from) {
      std::nth_element(values.begin() + std::ptrdiff_t(from), values.begin() + std::ptrdiff_t(k), values.end());
      from = k + 1;
    }
    out[i] = values[k];
  }
  return out;
}

}  // namespace meshsal
