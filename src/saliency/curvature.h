// meshsal: per-vertex normals and Taubin mean curvature (SPEC 1).
#pragma once
#include <vector>

#include "core/adjacency.h"
#include "meshsal/meshsal.h"

namespace meshsal {

// Area-weighted vertex normals (sum of un-normalised face normals, normalised);
// 3 doubles per vertex, zero where the sum vanishes.
std::vector<double> vertex_normals(const Mesh& mesh);

// Taubin mean curvature H_i = sum_j w_ij k_ij |T_ij|^2 per vertex; 0 for unreferenced
// vertices, for vertices whose normal vanishes and where all incident area is zero.
std::vector<double> mean_curvature(const Mesh& mesh, const Adjacency& adjacency,
                                   const std::vector<double>& normals, unsigned threads = 0);

}  // namespace meshsal
