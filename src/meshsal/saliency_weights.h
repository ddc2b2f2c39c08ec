// meshsal: the per-vertex quadric weights W of saliency-guided simplification (SPEC 2).
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "meshsal/mesh.h"

namespace meshsal {

struct SaliencyWeightOptions {
  double lambda = 100;            // amplification of salient vertices (--lambda)
  double alpha_percentile = 30;   // alpha = this percentile of Sm over mesh points
  // Not in the SPEC (default 0 = off): W is raised to at least floor * mean(W) over mesh
  // points, so that a vertex of near-zero saliency keeps some of its quadric and flat
  // regions are not collapsed with no regard to geometry at all.
  double floor = 0;
};

// Percentile p in [0, 100] of `values` over the entries with mask != 0 (all entries when
// mask is empty), by linear interpolation between order statistics (rank p/100 * (n-1)).
// Throws Error when no entry is selected or p is outside [0, 100].
double percentile(const std::vector<double>& values, const std::vector<uint8_t>& mask, double p);

// Smoothed saliency Sm = G(S, 3 eps) over the mesh points (SPEC 1 cutoff rule), with
// eps = eps_frac * bbox diagonal. For reusing a saliency PLY without recomputing it.
std::vector<double> smooth_saliency(const Mesh& mesh, const std::vector<double>& saliency,
                                    double eps_frac = 0.003, unsigned threads = 0);

// Reads S back from a saliency PLY written by `meshsal saliency` (its `quality` vertex
// property) for `mesh`. Throws Error when the file has no quality property, a quality is
// not finite, or the file belongs to another mesh: another vertex count, or a vertex at
// another position (beyond float precision: 1e-6 of the bounding-box diagonal), named.
std::vector<double> load_saliency_ply(const std::string& path, const Mesh& mesh);

// W(v) = lambda * Sm(v) if Sm(v) >= alpha else Sm(v), with alpha the alpha_percentile of Sm
// over the mesh points (is_point != 0); 0 for other vertices. `alpha_out` receives alpha.
// Throws Error on a size mismatch, lambda < 0, a percentile outside [0, 100] or a negative
// or non-finite Sm.
std::vector<double> saliency_weights(const std::vector<double>& smoothed,
                                     const std::vector<uint8_t>& is_point,
                                     const SaliencyWeightOptions& options,
                                     double* alpha_out = nullptr);

}  // namespace meshsal
