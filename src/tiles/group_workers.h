// meshsal (internal): the groups of a tiled simplification pass on every core. A pass's
// groups are independent (each simplifies its own piece from the pass's input), so they
// run side by side and the pieces come out the same on 1 worker or many; the drivers
// (simplify_tiled.cpp, disk_simplify.cpp) keep each group's outcome in its own slot and
// merge in group order.
#pragma once
#include <cstddef>
#include <functional>
#include <vector>

#include "meshsal/meshsal.h"

namespace meshsal {
namespace detail {

// How a pass's groups share `threads` (0 = all cores) when at most `concurrent` pieces may
// be held at once (a memory limit; 0 = no cap): `workers` groups at a time, each group's
// own steps on `inner` threads (the simplifier's edge costs).
struct GroupWorkers {
  unsigned workers = 1, inner = 1;
};
GroupWorkers group_workers(unsigned threads, unsigned concurrent, size_t groups);

// Calls body(g, worker) once for every group g this process runs (runs_group), on
// `workers` threads, the largest `sizes[g]` first (a pass's groups differ several-fold:
// the largest last would run alone). worker: 0 .. workers - 1, one group at a time each
// (a worker's scratch is its own). An exception from any group is rethrown here, once the
// others stopped.
void for_each_group(const TileExchange* exchange, const std::vector<size_t>& sizes, unsigned workers,
                    const std::function<void(size_t g, unsigned worker)>& body);

}  // namespace detail
}  // namespace meshsal
