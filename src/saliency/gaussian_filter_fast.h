// meshsal: the approximate Gaussian-weighted averages of `--method fast` (SPEC 5): each
// sigma's average is taken over per-cell aggregates (point count, value sum, centroid) of
// cells of sigma / c (c = 6) instead of over the points, so a vertex visits a fixed
// number of cells (~ pi (2 c)^2 on a surface) however dense the mesh is. The exact sweep in
// gaussian_filter.h is the oracle it is measured against.
#pragma once
#include <cstdint>
#include <functional>
#include <vector>

#include "meshsal/meshsal.h"
#include "saliency/gaussian_filter.h"

namespace meshsal {

// The method's parameters (docs/method.md); tests vary them, the library uses the defaults.
struct FastFilterParams {
  double cells_per_sigma = 6;  // aggregate cell edge = sigma / cells_per_sigma
  // Where cells hold at least this many points on average, the sums are taken once per
  // cell (at its centroid, with their gradients) and extrapolated linearly to its vertices;
  // elsewhere once per vertex. 0: always per cell; infinity: always per vertex.
  double points_per_query_cell = 2;
  // Dense sums are taken at the centroid of each group of the cells inside a cell of
  // query_factor cells per axis (1: each cell's own centroid) and extrapolated linearly,
  // their gradients with the cutoff's share taken from a shell shell_cells cells deep
  // inside the cutoff (0: none). Measured in docs/method.md: 2 and 1 take a quarter of
  // the queries of 1 and 0 at about the same error.
  int query_factor = 2;
  double shell_cells = 1;
};

// The same contract as gaussian_filter(): out[k][v] approximates G(values, v, sigmas[k]);
// 0 for vertices that are not mesh points (at most kMaxSigmas sigmas). stats->pairs counts
// (vertex, cell) pairs. With scope->take the sigmas' arrays go to it and none is returned.
// `scope` (may be null; filter_scope.h): the mesh is a tile of a larger one; its cells are
// the whole mesh's, complete where the tile holds every mesh point within 2 s + one cell of
// its queries, so each cell's aggregate is the whole mesh's (only the order of the sums
// over cells may differ: a tile's values agree with the whole mesh's to rounding).
std::vector<std::vector<double>> gaussian_filter_fast(
    const Mesh& mesh, const std::vector<uint8_t>& is_point, const std::vector<double>& values,
    const std::vector<double>& sigmas, unsigned threads = 0, FilterStats* stats = nullptr,
    const std::function<void(double)>& progress = {}, const FastFilterParams& params = {},
    const FilterScope* scope = nullptr);

// The edge of the fast method's cells for sigma over the points of `box`.
double fast_cell_edge(const BoundingBox& box, double sigma, const FastFilterParams& params = {});

// Per sigma, the occupied cells (of fast_cell_edge over `box`) whose lowest-index mesh
// point is flagged in `own`: summed over tiles that each own their vertices, the whole
// mesh's occupied cell count (FilterScope::occupied_cells), where every tile holds the
// whole cell of each point it owns.
std::vector<uint64_t> count_fast_cells(const Mesh& mesh, const std::vector<uint8_t>& is_point,
                                       const std::vector<uint8_t>& own, const BoundingBox& box,
                                       const std::vector<double>& sigmas,
                                       const FastFilterParams& params = {});

// The number of (v, x) mesh-point pairs with |x - v| < radius (v itself included) that the
// exact sweep would visit, estimated from up to 256 evenly spread sample points counted
// exactly (a few % off on scans). Linear in the point count.
double estimate_sweep_pairs(const Mesh& mesh, const std::vector<uint8_t>& is_point,
                            double radius);

}  // namespace meshsal
