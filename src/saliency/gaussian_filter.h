// meshsal: Gaussian-weighted averages of a per-vertex value at several sigmas in one
// neighbour sweep over a uniform grid (SPEC 1, "Gaussian-weighted average").
#pragma once
#include <cstdint>
#include <functional>
#include <vector>

#include "meshsal/meshsal.h"
#include "saliency/filter_scope.h"

namespace meshsal {

struct FilterStats {
  uint64_t pairs = 0;  // (v, x) pairs inside the largest cutoff radius, v itself included
};

// out[k][v] = sum C(x) exp(-|x-v|^2/(2 s_k^2)) / sum exp(...) over mesh points x with
// |x - v| < 2 s_k; 0 for vertices that are not mesh points. `sigmas` are absolute lengths.
// `progress` (may be empty) receives the finished fraction from the calling thread.
// `scope` (may be null): the mesh is a tile of a larger one (filter_scope.h); the values at
// its query vertices are then bit-equal to the whole mesh's where the tile holds every mesh
// point of the grid cells within 2 s of them (saliency_tiles.cpp's halo).
std::vector<std::vector<double>> gaussian_filter(
    const Mesh& mesh, const std::vector<uint8_t>& is_point, const std::vector<double>& values,
    const std::vector<double>& sigmas, unsigned threads = 0, FilterStats* stats = nullptr,
    const std::function<void(double)>& progress = {}, const FilterScope* scope = nullptr);

// The cell edge of the exact sweep's grid for these sigmas over the points of `frame`
// (what gaussian_filter lays), so that a tile's halo can cover whole cells.
double sweep_grid_cell(const std::vector<double>& sigmas, const GridFrame& frame);

// The same sums by brute force over all pairs, O(n^2): the test oracle.
std::vector<std::vector<double>> gaussian_filter_bruteforce(
    const Mesh& mesh, const std::vector<uint8_t>& is_point, const std::vector<double>& values,
    const std::vector<double>& sigmas);

}  // namespace meshsal
