// meshsal: a stable LSD radix sort of values by integer keys (up to 11 bits a pass, as many
// passes as the largest key needs, on several threads): linear where std::sort of
// (key, value) pairs is n log n. The fast method's cells (saliency/sparse_cells.cpp), the
// Morton order (core/morton_order.cpp) and the tiles' assembly sort with it.
#pragma once
#include <cstdint>
#include <vector>

namespace meshsal {

// Sorts key ascending and val along with it; equal keys keep their order (whatever the
// thread count: each thread takes a contiguous share and the shares are merged in order).
// Every key must be at most max_key. threads: 0 = all cores.
void radix_sort(std::vector<uint64_t>& key, std::vector<uint32_t>& val, uint64_t max_key, unsigned threads = 0);
void radix_sort(std::vector<uint32_t>& key, std::vector<uint32_t>& val, uint64_t max_key, unsigned threads = 0);

}  // namespace meshsal
