#include "core/kth_smallest.h"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <mutex>
#include <numeric>

#include "core/parallel.h"
#include "meshsal/meshsal.h"

namespace meshsal {
namespace {

// Below this many values one nth_element per k is as quick as the buckets' two passes.
constexpr size_t kBucketedFrom = size_t(1) << 18;
constexpr int kBucketBits = 16;

// The bits of x as an unsigned number in x's order (negatives' bits flipped, positives'
// sign bit set): a < b exactly when key(a) < key(b), for every pair but -0 and +0 (equal
// as numbers: a zero is returned as +0 on every path, see below).
uint64_t order_key(double x) {
  uint64_t u;
  std::memcpy(&u, &x, sizeof u);
  return (u >> 63) ? ~u : (u | (uint64_t(1) << 63));
}

uint32_t bucket_of(double x) { return uint32_t(order_key(x) >> (64 - kBucketBits)); }

// One nth_element per k, ascending, each over what lies above the previous one.
void select_in_place(std::vector<double>& values, const std::vector<size_t>& ks,
                     const std::vector<size_t>& order, std::vector<double>& out) {
  size_t from = 0;
  for (size_t i : order) {
    const size_t k = ks[i];
    if (k >= from) {
      std::nth_element(values.begin() + std::ptrdiff_t(from), values.begin() + std::ptrdiff_t(k), values.end());
      from = k + 1;
    }
    out[i] = values[k] == 0 ? 0.0 : values[k];  // -0 or +0, whichever a sort leaves: +0
  }
}

}  // namespace

std::vector<double> kth_smallest(std::vector<double>& values, const std::vector<size_t>& ks) {
  for (size_t k : ks)
    if (k >= values.size()) throw Error("internal: order statistic past the end");
  std::vector<size_t> order(ks.size());
  std::iota(order.begin(), order.end(), size_t(0));
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return ks[a] < ks[b]; });
  std::vector<double> out(ks.size());
  const size_t n = values.size();
  if (n < kBucketedFrom || resolve_threads(0) == 1) {
    select_in_place(values, ks, order, out);
    return out;
  }
  // On every core: count the values per bucket of their leading bits, find the bucket and
  // the rank inside it of each k, gather those buckets' values and select in them alone.
  // (A serial nth_element per percentile was a quarter of a second on 8.6M values.)
  std::vector<uint64_t> count(size_t(1) << kBucketBits, 0);
  std::mutex lock;
  const size_t share = (n + resolve_threads(0) - 1) / resolve_threads(0);  // a histogram a thread
  parallel_for(n, 0, share, [&](size_t begin, size_t end) {
    std::vector<uint64_t> mine(size_t(1) << kBucketBits, 0);
    for (size_t i = begin; i < end; ++i) ++mine[bucket_of(values[i])];
    std::lock_guard<std::mutex> hold(lock);
    for (size_t b = 0; b < mine.size(); ++b) count[b] += mine[b];
  });
  // slot[b]: where bucket b's values are gathered (-1: not needed).
  std::vector<int> slot(count.size(), -1);
  std::vector<uint32_t> wanted;                  // the buckets, by slot
  std::vector<std::pair<int, size_t>> at(ks.size());  // (slot, rank in the bucket) per k
  {
    size_t below = 0, b = 0;
    for (size_t i : order) {
      while (below + count[b] <= ks[i]) below += count[b++];
      if (slot[b] < 0) slot[b] = int(wanted.size()), wanted.push_back(uint32_t(b));
      at[i] = {slot[b], ks[i] - below};
    }
  }
  std::vector<std::vector<double>> gathered(wanted.size());
  for (size_t s = 0; s < wanted.size(); ++s) gathered[s].reserve(count[wanted[s]]);
  parallel_for(n, 0, share, [&](size_t begin, size_t end) {
    std::vector<std::vector<double>> mine(wanted.size());
    for (size_t i = begin; i < end; ++i)
      if (const int s = slot[bucket_of(values[i])]; s >= 0) mine[size_t(s)].push_back(values[i]);
    std::lock_guard<std::mutex> hold(lock);
    for (size_t s = 0; s < mine.size(); ++s) gathered[s].insert(gathered[s].end(), mine[s].begin(), mine[s].end());
  });
  // Within a bucket, the ks in ascending order again (the order of `order` kept).
  std::vector<std::vector<size_t>> ranks(wanted.size()), which(wanted.size());
  for (size_t i : order) ranks[size_t(at[i].first)].push_back(at[i].second), which[size_t(at[i].first)].push_back(i);
  for (size_t s = 0; s < wanted.size(); ++s) {
    std::vector<size_t> local(ranks[s].size());
    std::iota(local.begin(), local.end(), size_t(0));
    std::vector<double> got(ranks[s].size());
    select_in_place(gathered[s], ranks[s], local, got);
    for (size_t j = 0; j < got.size(); ++j) out[which[s][j]] = got[j];
  }
  return out;
}

}  // namespace meshsal
