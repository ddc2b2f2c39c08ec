// meshsal: the stable counting sort's placement, on a contiguous share of the items per
// thread: each share counts its keys, then places its items after the earlier shares' items
// of the same key, so the order is the same on 1 thread or many. The radix sort's passes
// (radix_sort.cpp) and the Morton renumbering's triangles (morton_order.cpp) use it.
#pragma once
#include <cstddef>
#include <vector>

#include "core/parallel.h"

namespace meshsal {

// Calls place(i, slot) once for every item i in [0, count) with its position in the stable
// order by key(i) (each key below `keys`), from `shares` threads. `counters` is scratch
// (shares x keys entries).
template <class Key, class Place>
void counting_sort_place(size_t count, size_t keys, size_t shares, std::vector<size_t>& counters, Key&& key,
                         Place&& place) {
  counters.assign(shares * keys, 0);
  auto share_of = [&](size_t s, size_t& b, size_t& e) { b = count * s / shares, e = count * (s + 1) / shares; };
  parallel_for(shares, unsigned(shares), 1, [&](size_t sb, size_t se) {
    for (size_t s = sb; s < se; ++s) {
      size_t* c = &counters[s * keys];
      size_t b, e;
      share_of(s, b, e);
      for (size_t i = b; i < e; ++i) c[key(i)]++;
    }
  });
  // Where each share's items of each key go: key by key, share by share (stable).
  size_t sum = 0;
  for (size_t k = 0; k < keys; ++k)
    for (size_t s = 0; s < shares; ++s) {
      const size_t here = counters[s * keys + k];
      counters[s * keys + k] = sum;
      sum += here;
    }
  parallel_for(shares, unsigned(shares), 1, [&](size_t sb, size_t se) {
    for (size_t s = sb; s < se; ++s) {
      size_t* c = &counters[s * keys];
      size_t b, e;
      share_of(s, b, e);
      for (size_t i = b; i < e; ++i) place(i, c[key(i)]++);
    }
  });
}

}  // namespace meshsal
