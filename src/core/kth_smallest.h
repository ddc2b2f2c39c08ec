// meshsal: order statistics without a full sort: the percentiles of a saliency map (colour
// limits, --json statistics) on a 10-million-vertex scan cost a sort's 1-2 s otherwise.
#pragma once
#include <cstddef>
#include <vector>

namespace meshsal {

// For each k in ks (each < values.size()), the value a full ascending sort of `values`
// would put at index k: the same numbers as sorting, in expected linear time, on every core
// for large inputs. `values` may be reordered. ks in any order; repeated ks allowed.
std::vector<double> kth_smallest(std::vector<double>& values, const std::vector<size_t>& ks);

}  // namespace meshsal
