// meshsal: a stable LSD radix sort of values by integer keys (8 bits a pass, as many passes
// as the largest key needs): linear where std::sort of (key, value) pairs is n log n. The
// fast method's cells (saliency/sparse_cells.cpp) and the tiles' assembly sort with it.
#pragma once
#include <cstdint>
#include <vector>

namespace meshsal {

// Sorts key ascending and val along with it; equal keys keep their order.
void radix_sort(std::vector<uint64_t>& key, std::vector<uint32_t>& val, uint64_t max_key);

}  // namespace meshsal
