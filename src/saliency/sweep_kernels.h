// meshsal: the CPU hot loops of the Gaussian averages, the exact sweep's (gaussian_filter.cpp)
// and the fast method's queries (gaussian_filter_fast.cpp): written once, in sweep_kernels.inc,
// and compiled twice, by sweep_kernels_baseline.cpp for baseline x86-64 and by
// sweep_kernels_avx2.cpp with -mavx2 -mfma (CMakeLists.txt, next to MESHSAL_ARCH);
// kernels() hands out the set that cpu_path() (cpu_dispatch.h) picks. Both sets run the same
// IEEE operations in the same order (-ffp-contract=off everywhere, no fma intrinsic), so
// they give the same bits.
#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

#include "meshsal/meshsal.h"
#include "saliency/sparse_cells.h"
#include "saliency/spatial_grid.h"

namespace meshsal::sweep {

constexpr int kMaxSigmas = 32;

// How each sigma's weight is obtained: a sigma that is half of another one has weight
// w(s) = w(2s)^4, so only the "base" sigmas need an exp (default scales: 12, 10, 8 eps).
struct KernelPlan {
  int count = 0;
  int parent[kMaxSigmas];  // -1: exp(-d2 * coef), else w[parent]^4; parents come first
  double coef[kMaxSigmas];  // 1 / (2 s^2)
  double cutoff2[kMaxSigmas];  // (2 s)^2: strict cutoff |x - v| < 2 s
  int slot[kMaxSigmas];  // output index of plan entry
  double radius2 = 0;  // largest cutoff
};

// What the exact sweep of a range of sorted slots reads and writes.
struct SweepArgs {
  const SpatialGrid* grid;
  const double* values;  // sorted, padded by 4
  const KernelPlan* plan;
  double* const* out;    // out[plan slot] -> the per-vertex averages of that sigma
};

// One sigma's aggregates, in the query grid's slot order, in float: centroid (relative to
// `anchor`), point count and value sum, padded by kAggregatePad empty far-away cells for
// 8-wide loads. Floats: half the bytes of doubles and twice the lanes per instruction;
// their rounding (6e-8 of the extent in a centroid, of a cell's value sum) is far below
// the error of the cells themselves (docs/method.md, "Fast method"). The anchor is the
// minimum of the filter's box (a tile's: the whole mesh's), so a tile, the whole mesh and
// the Vulkan twin (fast_query.comp) round every centroid and query point to the same
// floats and decide each cutoff alike.
constexpr size_t kAggregatePad = 8;
struct Aggregates {
  SpatialGrid grid;  // over the centroids: frame, order and cell starts (grid.x/y/z empty)
  double anchor[3];  // model coordinates of the floats' zero
  std::vector<float> x, y, z, count, sum;
};

// The occupied cells of a SparseCells in groups, each the cells inside one cell of
// `factor` cells per axis (gaussian_filter_fast.cpp, group_cells): group g holds the cells
// cell[start[g] .. start[g+1]-1], in ascending order. centroid: x, y, z of each group
// relative to the aggregates' anchor, its cells' centroids weighted by their point counts
// (fast_group_centroids.comp's operations), set by the fast filter where it queries them.
struct QueryGroups {
  std::vector<uint32_t> start, cell;
  std::vector<double> centroid;
};

// What the fast method's queries of one sigma read and write.
struct QueryArgs {
  const Mesh* mesh;
  const Aggregates* ag;
  const SparseCells* cells;
  const QueryGroups* groups;  // dense: the query groups
  const uint32_t* visit;      // sparse: the vertices in visiting order
  const double* values;
  double s, coef, cutoff2;
  double inv_s2;              // 1 / s^2: the gradients' scale
  // Dense: the cutoff's share of the gradient (see sweep_cells in sweep_kernels.inc):
  // candidates with shell2 <= d^2 < cutoff2 add shell_weight to their weight there.
  double shell2, shell_weight;
  double* out;                // per vertex
};

// One set of the hot loops. Each takes a range [begin, end) of the work a parallel_for
// hands out and adds the pairs it visited to *pairs.
struct Kernels {
  // The exact sweep of sorted slots [begin, end): the fixed plan of the default scales
  // (KernelPlan::is_default) or any plan.
  void (*sweep_default)(const SweepArgs& a, size_t begin, size_t end, uint64_t* pairs);
  void (*sweep_generic)(const SweepArgs& a, size_t begin, size_t end, uint64_t* pairs);
  // The fast method: per query group [begin, end) (dense; returns the vertices written) or
  // per vertex visit[begin .. end) (sparse; returns end - begin).
  size_t (*query_cells)(const QueryArgs& a, size_t begin, size_t end, uint64_t* pairs);
  size_t (*query_vertices)(const QueryArgs& a, size_t begin, size_t end, uint64_t* pairs);
};

extern const Kernels kBaselineKernels;
#ifdef MESHSAL_AVX2_KERNELS
extern const Kernels kAvx2Kernels;
#endif

// The set of cpu_path().
const Kernels& kernels();

}  // namespace meshsal::sweep
