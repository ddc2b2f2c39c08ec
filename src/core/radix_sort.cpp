#include "core/radix_sort.h"

#include <algorithm>

#include "core/parallel.h"

namespace meshsal {

namespace {

// Linear, where std::sort of (key, vertex) pairs took a third of a second per sigma on
// igea_loop2; on threads, where one thread took a second per sweep on a 10M-vertex scan.
template <class Key>
void radix_sort_keys(std::vector<Key>& key, std::vector<uint32_t>& val, uint64_t max_key, unsigned threads) {
  const size_t n = key.size();
  int bits = 0;
  while (bits < 64 && (max_key >> bits) > 0) ++bits;
  if (n < 2 || bits == 0) return;
  // Passes of equal width, at most 11 bits (2048 counters a share: they stay in cache).
  const int passes = (bits + 10) / 11, digit = (bits + passes - 1) / passes;
  const size_t buckets = size_t(1) << digit;
  // One share per thread, at least 64K keys each.
  const size_t shares = std::max<size_t>(1, std::min<size_t>(resolve_threads(threads), n >> 16));
  std::vector<Key> key2(n);
  std::vector<uint32_t> val2(n);
  std::vector<size_t> count(shares * buckets);
  for (int shift = 0; shift < bits; shift += digit) {
    const Key mask = Key((uint64_t(1) << digit) - 1);
    std::fill(count.begin(), count.end(), 0);
    parallel_for(shares, unsigned(shares), 1, [&](size_t b, size_t e) {
      for (size_t t = b; t < e; ++t) {
        size_t* c = &count[t * buckets];
        for (size_t i = n * t / shares; i < n * (t + 1) / shares; ++i) c[(key[i] >> shift) & mask]++;
      }
    });
    // Where each share's keys of each digit go: digit by digit, share by share (stable).
    size_t sum = 0;
    for (size_t d = 0; d < buckets; ++d)
      for (size_t t = 0; t < shares; ++t) {
        const size_t here = count[t * buckets + d];
        count[t * buckets + d] = sum;
        sum += here;
      }
    parallel_for(shares, unsigned(shares), 1, [&](size_t b, size_t e) {
      for (size_t t = b; t < e; ++t) {
        size_t* c = &count[t * buckets];
        for (size_t i = n * t / shares; i < n * (t + 1) / shares; ++i) {
          const size_t to = c[(key[i] >> shift) & mask]++;
          key2[to] = key[i];
          val2[to] = val[i];
        }
      }
    });
    key.swap(key2);
    val.swap(val2);
  }
}

}  // namespace

void radix_sort(std::vector<uint64_t>& key, std::vector<uint32_t>& val, uint64_t max_key, unsigned threads) {
  radix_sort_keys(key, val, max_key, threads);
}

void radix_sort(std::vector<uint32_t>& key, std::vector<uint32_t>& val, uint64_t max_key, unsigned threads) {
  radix_sort_keys(key, val, max_key, threads);
}

}  // namespace meshsal
