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

}  // namespace meshsal
