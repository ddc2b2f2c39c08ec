// meshsal: the per-vertex quadric weights W of saliency-guided simplification (SPEC 2).
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "meshsal/meshsal.h"

namespace meshsal {

// Percentile p in [0, 100] of `values` over the entries with mask != 0 (all entries when
// mask is empty), by linear interpolation between order statistics (rank p/100 * (n-1)).
// Throws Error when no entry is selected or p is outside [0, 100].
double percentile(const std::vector<double>& values, const std::vector<uint8_t>& mask, double p);

}  // namespace meshsal
