// meshsal: how far an approximate saliency result (`--method fast`) is from the exact one on
// the same mesh: the figures SPEC section 5 defines the fast method by.
#pragma once
#include <vector>

#include "meshsal/meshsal.h"

namespace meshsal {

struct MethodError {
  double correlation = 0;    // Pearson correlation of the final saliency over mesh points
  double top30_overlap = 0;  // share of the exact top-30% mesh points also in approx's top 30%
  // Per raw map i: mean and max over mesh points of |approx - exact| / max_v exact (each
  // map's maximum: a per-vertex ratio would explode where the exact map is ~0).
  std::vector<double> raw_mean, raw_max;
};

// Throws Error when the two results do not belong to the same mesh and scales.
MethodError method_error(const SaliencyResult& exact, const SaliencyResult& approx);

// Indices of the ceil(share x points) mesh points with the highest values (ties: lower index).
std::vector<size_t> top_share(const std::vector<double>& values, const std::vector<uint8_t>& is_point,
                              double share);

}  // namespace meshsal
