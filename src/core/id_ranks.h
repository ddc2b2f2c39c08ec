// meshsal: the distinct ids of a list and each entry's rank among them, in linear time (a
// radix sort): what cutting a piece out of a larger mesh needs to renumber its corners
// (tiles/tile_pieces.cpp, tiles/disk_simplify.cpp), where sorting the corners and
// searching each one took 40% of a tiled simplification.
#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

namespace meshsal {

// `distinct` = the distinct values of ids[0, n), increasing; rank[i] = the position of
// ids[i] in `distinct` (rank has n entries). Every id must be at most max_id. threads: as
// radix_sort (0 = all cores; 1 where the caller already runs on every core).
void rank_ids(const uint32_t* ids, size_t n, uint32_t max_id, std::vector<uint32_t>& distinct,
              std::vector<uint32_t>& rank, unsigned threads = 1);

}  // namespace meshsal
