// streamed_percentile(), see streamed_percentile.h.
#include "core/streamed_percentile.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "meshsal/meshsal.h"

namespace meshsal {

namespace {
constexpr size_t kBins = 65536;
}  // namespace

double streamed_kth(const ValueStream& stream, uint64_t k, size_t cap) {
  // The values in [lo, hi] are the candidates; `below` values lie under lo.
  double lo = -HUGE_VAL, hi = HUGE_VAL;
  uint64_t below = 0;
  for (;;) {
    uint64_t count = 0;
    double min = HUGE_VAL, max = -HUGE_VAL;
    stream([&](double x) {
      if (x < lo || x > hi) return;
      ++count;
      min = std::min(min, x);
      max = std::max(max, x);
    });
    if (min == max) return min;
    if (count <= cap) {
      std::vector<double> v;
      v.reserve(count);
      stream([&](double x) {
        if (x >= lo && x <= hi) v.push_back(x);
      });
      std::nth_element(v.begin(), v.begin() + (k - below), v.end());
      return v[k - below];
    }
    // A bin's values never meet another's (the binning is monotone), so the bin holding
    // the k-th value gives the next range: its own smallest and largest value.
    std::vector<uint64_t> n(kBins, 0);
    std::vector<double> bmin(kBins, HUGE_VAL), bmax(kBins, -HUGE_VAL);
    const double scale = double(kBins) / (max - min);
    stream([&](double x) {
      if (x < lo || x > hi) return;
      const size_t b = std::min(kBins - 1, size_t((x - min) * scale));
      ++n[b];
      bmin[b] = std::min(bmin[b], x);
      bmax[b] = std::max(bmax[b], x);
    });
    size_t b = 0;
    while (below + n[b] <= k) below += n[b++];
    lo = bmin[b];
    hi = bmax[b];
  }
}

double streamed_percentile(const ValueStream& stream, uint64_t n, double p, size_t cap) {
  if (!(p >= 0 && p <= 100)) throw Error("percentile must be in [0, 100], got " + std::to_string(p));
  if (n == 0) throw Error("percentile of an empty set");
  // As percentile(): linear interpolation between order statistics at rank p/100 * (n-1).
  const double rank = p / 100 * double(n - 1);
  const uint64_t lo = uint64_t(std::floor(rank));
  const uint64_t hi = std::min(lo + 1, n - 1);
  const double a = streamed_kth(stream, lo, cap);
  if (hi == lo) return a;
  const double b = streamed_kth(stream, hi, cap);
  return a + (rank - double(lo)) * (b - a);
}

}  // namespace meshsal
