// meshsal: the first index of a range that passes a test, found on every core: the loaded
// mesh's checks (finite coordinates, indices in range) name the first offender, as a serial
// loop would, without a serial pass over a 10-million-vertex scan's arrays.
#pragma once
#include <atomic>
#include <cstddef>

#include "core/parallel.h"

namespace meshsal {

// The smallest i in [0, n) with test(i), or n when none passes. Chunks that start past an
// offender already found are skipped.
template <class Test>
size_t first_index_where(size_t n, Test&& test) {
  std::atomic<size_t> first{n};
  parallel_for(n, 0, size_t(1) << 18, [&](size_t begin, size_t end) {
    for (size_t i = begin; i < end && i < first.load(std::memory_order_relaxed); ++i)
      if (test(i)) {
        size_t seen = first.load();
        while (i < seen && !first.compare_exchange_weak(seen, i)) {
        }
        return;
      }
  });
  return first.load();
}

}  // namespace meshsal
