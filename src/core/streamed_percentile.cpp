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

std::vector<double> streamed_kths(const ValueStream& stream, const std::vector<uint64_t>& ks, size_t cap) {
  // Per k, the values in [lo, hi] are the candidates; `below` values lie under lo.
  struct Search {
    uint64_t k, below = 0, count = 0;
    double lo = -HUGE_VAL, hi = HUGE_VAL, min = HUGE_VAL, max = -HUGE_VAL;
    bool done = false;
    double value = 0;
    std::vector<double> kept;                  // a range small enough, selected in memory
    std::vector<uint64_t> n;                   // a range narrowed: its histogram
    std::vector<double> bmin, bmax;
    bool in(double x) const { return x >= lo && x <= hi; }
  };
  std::vector<Search> s(ks.size());
  for (size_t i = 0; i < ks.size(); ++i) s[i].k = ks[i];
  auto open = [&] {
    std::vector<Search*> v;
    for (Search& x : s)
      if (!x.done) v.push_back(&x);
    return v;
  };
  for (std::vector<Search*> now = open(); !now.empty(); now = open()) {
    for (Search* x : now) x->count = 0, x->min = HUGE_VAL, x->max = -HUGE_VAL;
    stream([&](double v) {
      for (Search* x : now)
        if (x->in(v)) {
          ++x->count;
          x->min = std::min(x->min, v);
          x->max = std::max(x->max, v);
        }
    });
    std::vector<Search*> collect, narrow;
    for (Search* x : now) {
      if (x->min == x->max) {
        x->done = true, x->value = x->min;
      } else if (x->count <= cap) {
        x->kept.reserve(x->count);
        collect.push_back(x);
      } else {
        x->n.assign(kBins, 0), x->bmin.assign(kBins, HUGE_VAL), x->bmax.assign(kBins, -HUGE_VAL);
        narrow.push_back(x);
      }
    }
    if (collect.empty() && narrow.empty()) continue;
    // One pass for both: the small ranges' values kept, the others' binned.
    stream([&](double v) {
      for (Search* x : collect)
        if (x->in(v)) x->kept.push_back(v);
      for (Search* x : narrow) {
        if (!x->in(v)) continue;
        const size_t b = std::min(kBins - 1, size_t((v - x->min) * (double(kBins) / (x->max - x->min))));
        ++x->n[b];
        x->bmin[b] = std::min(x->bmin[b], v);
        x->bmax[b] = std::max(x->bmax[b], v);
      }
    });
    for (Search* x : collect) {
      std::nth_element(x->kept.begin(), x->kept.begin() + long(x->k - x->below), x->kept.end());
      x->done = true, x->value = x->kept[x->k - x->below];
      std::vector<double>().swap(x->kept);
    }
    // A bin's values never meet another's (the binning is monotone), so the bin holding
    // the k-th value gives the next range: its own smallest and largest value.
    for (Search* x : narrow) {
      size_t b = 0;
      while (x->below + x->n[b] <= x->k) x->below += x->n[b++];
      x->lo = x->bmin[b], x->hi = x->bmax[b];
      std::vector<uint64_t>().swap(x->n);
      std::vector<double>().swap(x->bmin), std::vector<double>().swap(x->bmax);
    }
  }
  std::vector<double> out;
  for (const Search& x : s) out.push_back(x.value);
  return out;
}

double streamed_kth(const ValueStream& stream, uint64_t k, size_t cap) { return streamed_kths(stream, {k}, cap)[0]; }

double streamed_percentile(const ValueStream& stream, uint64_t n, double p, size_t cap) {
  if (!(p >= 0 && p <= 100)) throw Error("percentile must be in [0, 100], got " + std::to_string(p));
  if (n == 0) throw Error("percentile of an empty set");
  // As percentile(): linear interpolation between order statistics at rank p/100 * (n-1).
  const double rank = p / 100 * double(n - 1);
  const uint64_t lo = uint64_t(std::floor(rank));
  const uint64_t hi = std::min(lo + 1, n - 1);
  const std::vector<double> v = streamed_kths(stream, hi == lo ? std::vector<uint64_t>{lo} : std::vector<uint64_t>{lo, hi}, cap);
  if (hi == lo) return v[0];
  return v[0] + (rank - double(lo)) * (v[1] - v[0]);
}

}  // namespace meshsal
