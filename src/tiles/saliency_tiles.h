// meshsal: saliency one tile at a time (SaliencyOptions::tiles). Saliency is local but for
// two values per scale, so the bounding box is cut into cubic tiles and each tile computes
// its own vertices from a sub-mesh with a halo:
//   own    the mesh points in the tile's cube;
//   query  the points whose raw maps it needs: own, their 1-rings (the local-maximum test)
//          and, with smoothing, every point within 6 eps (+ cells) of own (Sm = G(S, 3 eps));
//   source every mesh point within the largest cutoff (+ cells) of a query point, with all
//          its triangles, so that its curvature and the sweeps' cells are the whole mesh's.
// The phases, each a plain function of one tile so that any driver (one process, a disk
// of tiles, MPI ranks) can run them:
//   0 (fast method only) count_tile_cells: the whole mesh's occupied cells, summed;
//   1 tile_raw_maps: curvature, averages and raw maps at the queries; each scale's maximum
//     (lowest index on ties) reduced over tiles;
//   2 tile_local_maxima: the local maxima of own points, merged in vertex order over tiles
//     into mbar (the same sum in the same order as suppress());
//   3 tile_finish: S (and Sm) at own points.
// The grids are laid over the whole mesh (GridFrame), so the exact method gives the same
// bits as compute_saliency_cpu.
#pragma once
#include <cstdint>
#include <functional>
#include <vector>

#include "core/mesh_points.h"
#include "meshsal/meshsal.h"

namespace meshsal {

// What every tile of a run shares, from the whole mesh's mesh points and the options.
struct TilePlan {
  Method method = Method::Exact;  // Exact or Fast
  std::vector<double> scales;
  bool smoothed = false;
  unsigned threads = 0;
  BoundingBox box;          // the whole mesh's mesh points
  uint64_t points = 0;      // and their count
  double eps = 0;
  double tile_edge = 0;     // the tiles' cube edge
  int tiles[3] = {1, 1, 1}; // tiles per axis
  double query_margin = 0;  // around own points: smoothing's reach (0 without smoothing)
  double source_margin = 0; // around query points: the filter's reach
  // Fast method: the whole mesh's occupied cells per filter sigma, then for 3 eps (phase 0).
  std::vector<uint64_t> fast_cells;
};

// The plan for `tiles` cubes along the longest axis of `box` (at least 1).
TilePlan make_tile_plan(const BoundingBox& box, uint64_t points, const SaliencyOptions& options,
                        unsigned tiles);

size_t tile_count(const TilePlan& plan);

// The tile of a point inside plan.box.
size_t tile_of(const TilePlan& plan, const float* p);

// The sigmas of phase 0's counts: the filter's (filter_sigma_units x eps), then 3 eps.
std::vector<double> tile_cell_sigmas(const TilePlan& plan);

// One tile's sub-mesh: every triangle with a corner among its source points; its vertices
// in whole-mesh order (so every sum runs in the whole mesh's order).
struct TileMesh {
  Mesh mesh;                      // positions as in the whole mesh, local triangles
  std::vector<uint32_t> global;   // tile vertex -> whole-mesh vertex, ascending
  std::vector<uint8_t> own;       // per tile vertex
  std::vector<uint8_t> query;     // per tile vertex
  size_t own_count = 0;
};

// One triangle as the tiles see it: its index in the whole mesh and its corners.
struct TileFace {
  uint32_t face;
  uint32_t c[3];
};

// Where sub-meshes come from (a mesh in memory, or tile files on disk): each tile's bucket,
// every triangle with a corner (a mesh point) in its cube, in any order, duplicates allowed;
// and the positions of sorted, distinct vertices (3 floats each).
struct TileSource {
  std::function<void(size_t tile, std::vector<TileFace>& into)> bucket;
  std::function<void(const std::vector<uint32_t>& sorted, std::vector<float>& xyz)> positions;
};

// Tile t's sub-mesh: own points and their 1-rings from its bucket, then every triangle with
// a corner in the source box from the buckets of the tiles that box meets.
TileMesh assemble_tile(const TilePlan& plan, size_t t, const TileSource& source);

// The buckets of a mesh in memory (CSR: tile -> triangles), for its TileSource.
struct TileBuckets {
  std::vector<uint64_t> start;  // tile_count + 1
  std::vector<uint32_t> faces;
};
TileBuckets bucket_triangles(const Mesh& mesh, const TilePlan& plan);
TileSource memory_tile_source(const Mesh& mesh, const TileBuckets& buckets);

// Phase 0: per tile_cell_sigmas() sigma, the occupied cells whose lowest point is own; the
// tile need only be assembled with cell_count_plan()'s halo (two of the largest cells).
std::vector<uint64_t> count_tile_cells(const TileMesh& tile, const TilePlan& plan);
TilePlan cell_count_plan(const TilePlan& plan);

// Phase 1's result, kept until the tile finishes: per query point, in whole-mesh order.
struct TileRaw {
  std::vector<uint32_t> global;
  std::vector<float> positions;            // 3 per query point
  std::vector<uint8_t> own;
  std::vector<double> curvature;
  std::vector<std::vector<double>> raw;    // [scale][query point]
  std::vector<uint32_t> ring_offsets;      // own points' 1-rings, in query indices
  std::vector<uint32_t> ring;
  uint64_t pairs = 0;                      // the sweep's pairs (queries' work)
};

TileRaw tile_raw_maps(TileMesh tile, const TilePlan& plan);  // consumes the tile

// Each scale's maximum over the mesh points and the lowest vertex attaining it.
struct ScaleMax {
  double max = 0;
  uint32_t vertex = UINT32_MAX;  // none yet
};
std::vector<ScaleMax> tile_scale_max(const TileRaw& tile);
void merge_scale_max(std::vector<ScaleMax>& into, const std::vector<ScaleMax>& from);

// Phase 2: per scale, the own local maxima (vertex, normalised value) in vertex order.
struct LocalMax {
  uint32_t vertex;
  double value;
};
std::vector<std::vector<LocalMax>> tile_local_maxima(const TileRaw& tile,
                                                     const std::vector<ScaleMax>& max);
// mbar of one scale from every tile's local maxima: sorted by vertex, summed in that order
// without the global maximum's vertex, as suppress() sums them.
double mbar_of(std::vector<LocalMax> maxima, const ScaleMax& max);

// Phase 3: the own points' results.
struct TileResult {
  std::vector<uint32_t> global;            // own points, ascending
  std::vector<double> curvature, saliency, smoothed;
  std::vector<std::vector<double>> raw;    // [scale][own point]
};
TileResult tile_finish(const TileRaw& tile, const TilePlan& plan, const std::vector<ScaleMax>& max,
                       const std::vector<double>& mbar);

// A tiled run of a mesh in memory (compute_saliency with options.tiles > 1): phases 0-3
// over this process's tiles, reductions through options.exchange when given.
SaliencyResult compute_saliency_tiled(const Mesh& mesh, const SaliencyOptions& options);

}  // namespace meshsal
