// meshsal: mesh saliency (Lee, Varshney, Jacobs 2005) exactly as SPEC section 1 fixes it.
#pragma once
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "meshsal/meshsal.h"

namespace meshsal {

// The CPU reference path.
SaliencyResult compute_saliency_cpu(const Mesh& mesh, const SaliencyOptions& options);

// The distinct sigmas (in eps units) the filter needs for these scales: each k and 2k, sorted.
std::vector<double> filter_sigma_units(const std::vector<double>& scales);

// Limits of the options: eps_frac in (0, kMaxEpsFrac], each scale in (0, kMaxScale], and
// 2 x largest scale x eps_frac <= 1 (the widest Gaussian at most the bounding-box diagonal).
constexpr double kMaxEpsFrac = 0.1;
constexpr double kMaxScale = 100;
constexpr unsigned kMaxTiles = 64;  // SaliencyOptions::tiles

// Throws Error when options break the limits above (compute_saliency* call it).
void check_saliency_options(const SaliencyOptions& options);

// options.method with Auto decided for this mesh (Fast when the exact sweep's estimated
// pairs pass kAutoPairBudget, with a notice); compute_saliency and smooth_saliency use it.
Method resolve_method(const Mesh& mesh, const SaliencyOptions& options);

}  // namespace meshsal
