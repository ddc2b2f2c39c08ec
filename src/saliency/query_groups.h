// meshsal: the fast method's query groups (sweep_kernels.h, QueryGroups): the occupied cells
// of a SparseCells gathered by the coarser cell of `factor` cells per axis that holds them,
// so that the dense sums are taken once per group. The GPU twin (gpu/gpu_fast_cells.cpp)
// groups its cells with the same function.
#pragma once
#include <cstdint>
#include <vector>

#include "saliency/sweep_kernels.h"

namespace meshsal {

// keys: the occupied cells' keys (cell_key over dims), ascending. Groups in ascending order
// of their coarse key, each group's cells in ascending order; factor 1: a group per cell.
sweep::QueryGroups group_cells(const std::vector<uint64_t>& keys, const uint64_t dims[3],
                               int factor, unsigned threads = 0);
sweep::QueryGroups group_cells(const std::vector<uint32_t>& keys, const uint64_t dims[3],
                               int factor, unsigned threads = 0);

// The same by sorting (std::stable_sort): the oracle the tests hold group_cells to.
sweep::QueryGroups group_cells_reference(const std::vector<uint64_t>& keys, const uint64_t dims[3],
                                         int factor);

}  // namespace meshsal
