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

// Throws Error for a lambda, floor, gamma or cap out of range.
void check_weight_options(const SaliencyWeightOptions& options);

// W of one mesh point before the floor, for the curves that depend on Sm and alpha alone
// (Threshold, Continuous; Rank needs every point's rank): saliency_weights() per point.
double curve_weight(double smoothed, double alpha, const SaliencyWeightOptions& options);

// The floor under W: options.floor times the mean W (sum over n mesh points), or 1 when
// that is 0 (nothing salient: plain quadrics).
double weight_floor(double sum, size_t n, const SaliencyWeightOptions& options);

}  // namespace meshsal
