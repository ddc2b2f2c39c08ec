#include "core/radix_sort.h"

#include <algorithm>

#include "core/counting_sort.h"
#include "core/parallel.h"

namespace meshsal {

namespace {

// One stable counting pass of `count` keys from (key, val) to (key2, val2) on the digit
// (key >> shift) & (buckets - 1), on `shares` contiguous shares of the input (one per
// thread). Afterwards the last share's counters hold each digit's end.
template <class Key>
void counting_pass(const Key* key, const uint32_t* val, Key* key2, uint32_t* val2, size_t count, int shift,
                   size_t buckets, size_t shares, std::vector<size_t>& counters) {
  const Key mask = Key(buckets - 1);
  counting_sort_place(
      count, buckets, shares, counters, [&](size_t i) { return size_t((key[i] >> shift) & mask); },
      [&](size_t i, size_t to) {
        key2[to] = key[i];
        val2[to] = val[i];
      });
}

// Linear, where std::sort of (key, vertex) pairs took a third of a second per sigma on
// igea_loop2; on threads, where one thread took a second per sweep on a 10M-vertex scan.
// Keys of more than 11 bits and arrays of more than 2^16 go most significant digit first:
// one pass over the whole array by the top digit (up to 11 bits), then each of its buckets
// (a few thousand keys: they stay in the cache) least significant digit first. Every pass
// is stable, so the result is the stable sort's, as an all-LSD sort gives it; the whole
// array is crossed once instead of once per digit (3 times for a 30-bit cell key).
template <class Key>
void radix_sort_keys(std::vector<Key>& key, std::vector<uint32_t>& val, uint64_t max_key, unsigned threads) {
  const size_t n = key.size();
  int bits = 0;
  while (bits < 64 && (max_key >> bits) > 0) ++bits;
  if (n < 2 || bits == 0) return;
  // One share per thread, at least 64K keys each.
  const size_t shares = std::max<size_t>(1, std::min<size_t>(resolve_threads(threads), n >> 16));
  std::vector<Key> key2(n);
  std::vector<uint32_t> val2(n);
  std::vector<size_t> counters;
  // Passes of equal width, at most 11 bits (2048 counters a share: they stay in cache).
  auto passes_for = [](int digit_bits) { return (digit_bits + 10) / 11; };
  auto lsd = [&](Key* k, uint32_t* v, Key* k2, uint32_t* v2, size_t count, int low_bits, size_t parts,
                 std::vector<size_t>& c) {
    // Returns whether the result ended in (k2, v2).
    if (low_bits == 0) return false;
    const int passes = passes_for(low_bits), digit = (low_bits + passes - 1) / passes;
    bool in_second = false;
    for (int shift = 0; shift < low_bits; shift += digit) {
      if (!in_second)
        counting_pass(k, v, k2, v2, count, shift, size_t(1) << digit, parts, c);
      else
        counting_pass(k2, v2, k, v, count, shift, size_t(1) << digit, parts, c);
      in_second = !in_second;
    }
    return in_second;
  };
  if (bits <= 11 || n <= (size_t(1) << 16)) {
    if (lsd(key.data(), val.data(), key2.data(), val2.data(), n, bits, shares, counters)) {
      key.swap(key2);
      val.swap(val2);
    }
    return;
  }
  const int top = std::min(11, bits - 1), low = bits - top;
  const size_t buckets = size_t(1) << top;
  // The top digit over the whole array, into (key2, val2); then where each bucket lies.
  counting_pass(key.data(), val.data(), key2.data(), val2.data(), n, low, buckets, shares, counters);
  // (The last share's counters now hold each digit's end.)
  std::vector<size_t> start(buckets + 1, 0);
  for (size_t d = 0; d < buckets; ++d) start[d + 1] = counters[(shares - 1) * buckets + d];
  // Each bucket on one thread, its low digits in place between the two arrays. Every
  // bucket takes the same number of passes, so all end in the same array.
  const int passes = passes_for(low);
  parallel_for(buckets, threads, 16, [&](size_t db, size_t de) {
    std::vector<size_t> c;
    for (size_t d = db; d < de; ++d) {
      const size_t b = start[d], count = start[d + 1] - b;
      if (count > 1) lsd(key2.data() + b, val2.data() + b, key.data() + b, val.data() + b, count, low, 1, c);
      else if (count == 1 && passes % 2 == 1) key[b] = key2[b], val[b] = val2[b];
    }
  });
  // After an odd number of low passes the buckets are back in (key, val).
  if (passes % 2 == 0) {
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
