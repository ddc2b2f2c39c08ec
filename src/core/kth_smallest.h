// meshsal: order statistics without a full sort: the percentiles of a saliency map (colour
// limits, --json statistics) on a 10-million-vertex scan cost a sort's 1-2 s otherwise.
#pragma once
#include <cstddef>
#include <vector>

namespace meshsal {

// For each k in ks (each < values.size()), the value a full ascending sort of `values`
// would put at index k: the same numbers as sorting, in expected linear time, on every core
// for large inputs. `values` may be reordered. ks in any order; repeated ks allowed. A zero
// comes back as +0 (a sort may leave -0 or +0 there: the same bits on any thread count).
// NaN has no place in a sort: values must not hold any (callers drop or refuse them).
std::vector<double> kth_smallest(std::vector<double>& values, const std::vector<size_t>& ks);

}  // namespace meshsal
