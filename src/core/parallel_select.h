// meshsal: the entries of a range that pass a test, in order, found on several threads:
// each thread takes a contiguous share, counts what passes, then writes it after the
// shares before it, so the list is the serial loop's whatever the thread count. The
// tiles' filters select their points so once per sigma (a serial pass over a few million
// points was a third of a tile's filter time).
#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/parallel.h"

namespace meshsal {

// out = value(i) for every i in [0, n) with keep(i), in increasing i.
template <class Keep, class Value, class Out>
void parallel_select(size_t n, unsigned threads, Keep&& keep, Value&& value, std::vector<Out>& out) {
  // Shares of at least 64K entries: a share's count pass and write pass both read it.
  const size_t shares = std::max<size_t>(1, std::min<size_t>(resolve_threads(threads), n >> 16));
  std::vector<size_t> start(shares + 1, 0);
  parallel_for(shares, unsigned(shares), 1, [&](size_t s0, size_t s1) {
    for (size_t s = s0; s < s1; ++s) {
      size_t count = 0;
      for (size_t i = n * s / shares; i < n * (s + 1) / shares; ++i) count += keep(i) ? 1 : 0;
      start[s + 1] = count;
    }
  });
  for (size_t s = 0; s < shares; ++s) start[s + 1] += start[s];
  out.resize(start[shares]);
  parallel_for(shares, unsigned(shares), 1, [&](size_t s0, size_t s1) {
    for (size_t s = s0; s < s1; ++s) {
      size_t at = start[s];
      for (size_t i = n * s / shares; i < n * (s + 1) / shares; ++i)
        if (keep(i)) out[at++] = value(i);
    }
  });
}

}  // namespace meshsal
