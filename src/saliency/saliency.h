// meshsal: mesh saliency (Lee, Varshney, Jacobs 2005) exactly as SPEC section 1 fixes it.
#pragma once
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "meshsal/meshsal.h"

namespace meshsal {

// The CPU reference path (Method::Fast goes to compute_saliency_fast_cpu).
SaliencyResult compute_saliency_cpu(const Mesh& mesh, const SaliencyOptions& options);

// The fast method on the CPU (saliency_fast_cpu.cpp): the same stages without 1-rings,
// one sigma and one raw map at a time.
SaliencyResult compute_saliency_fast_cpu(const Mesh& mesh, const SaliencyOptions& options);

// The order compute_saliency_fast_cpu runs the scales in (indices into scales): chains
// k, 2k, 4k, ... first, each from the smallest scale left, so that the average at 2k is
// still held when scale 2k runs. A permutation of 0 .. scales.size() - 1.
std::vector<size_t> fast_scale_order(const std::vector<double>& scales);

// The distinct sigmas (in eps units) the filter needs for these scales: each k and 2k, sorted.
std::vector<double> filter_sigma_units(const std::vector<double>& scales);

// Limits of the options: eps_frac in (0, kMaxEpsFrac], 1..kMaxScaleCount (meshsal/saliency.h) scales each in
// (0, kMaxScale], and 2 x largest scale x eps_frac <= 1 (the widest Gaussian at most the
// bounding-box diagonal).
constexpr double kMaxEpsFrac = 0.1;
constexpr double kMaxScale = 100;
constexpr unsigned kMaxTiles = 64;  // SaliencyOptions::tiles

// Throws Error when options break the limits above (compute_saliency* call it).
void check_saliency_options(const SaliencyOptions& options);

}  // namespace meshsal
