// meshsal: saliency one tile at a time (SaliencyOptions::tiles). Saliency is local but for
// two values per scale, so the bounding box is cut into cubic tiles and each tile computes
// its own vertices from the points around it (a halo):
//   own    the mesh points in the tile's cube;
//   query  the points whose raw maps it needs: own, their 1-rings (the local-maximum test)
//          and, with smoothing, every point within 6 eps (+ cells) of own (Sm = G(S, 3 eps));
//   source every mesh point within the largest cutoff (+ cells) of a query point, with its
//          curvature (phase C), so that the sweeps' cells are the whole mesh's.
// The phases, each a plain function of one tile so that any driver (one process, a disk
// of tiles, MPI ranks) can run them:
//   C tile_curvature: the own points' curvature from the tile's own bucket alone (an own
//     point has all its triangles there), kept with their positions for every later phase,
//     its neighbours' included: a halo is then points (positions and H), not triangles;
//   0 (fast method only) tile_cells: the whole mesh's occupied cells, from each tile's own
//     points (the cells inside it counted, those across its faces merged over tiles);
//   1 tile_raw_maps: averages and raw maps at the queries over the source points; each
//     scale's maximum (lowest index on ties) reduced over tiles;
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

// The tile column along axis a of coordinate x: floor, clamped to [0, tiles - 1] (beyond
// the box's edges by rounding, or a box's margins; NaN to 0).
inline size_t tile_column(const TilePlan& plan, double x, int a) {
  const double f = (x - plan.box.min[a]) / plan.tile_edge;
  const size_t last = size_t(plan.tiles[a] - 1);
  return f >= double(last) ? last : f >= 1 ? size_t(f) : 0;
}

// The tile of a point inside plan.box (inline: every corner of every triangle asks it).
inline size_t tile_of(const TilePlan& plan, const float* p) {
  return (tile_column(plan, p[2], 2) * size_t(plan.tiles[1]) + tile_column(plan, p[1], 1)) * size_t(plan.tiles[0]) +
         tile_column(plan, p[0], 0);
}

// Tile t's cube (its column along each axis times the tile edge; the last column's reaches
// the box's face: tile_of clamps there).
BoundingBox tile_cube(const TilePlan& plan, size_t t);

// The sigmas of phase 0's counts: the filter's (filter_sigma_units x eps), then 3 eps.
std::vector<double> tile_cell_sigmas(const TilePlan& plan);

// One triangle as the tiles see it: its index in the whole mesh and its corners.
struct TileFace {
  uint32_t face;
  uint32_t c[3];
};

// Where the triangles come from (a mesh in memory, or tile files on disk): each tile's
// bucket, every triangle with a corner (a mesh point) in its cube, in any order, duplicates
// allowed; and the positions of sorted, distinct vertices (3 floats each).
struct TileSource {
  std::function<void(size_t tile, std::vector<TileFace>& into)> bucket;
  std::function<void(const std::vector<uint32_t>& sorted, std::vector<float>& xyz)> positions;
};

// The buckets of a mesh in memory (CSR: tile -> triangles), for its TileSource.
struct TileBuckets {
  std::vector<uint64_t> start;  // tile_count + 1
  std::vector<uint32_t> faces;
};
TileBuckets bucket_triangles(const Mesh& mesh, const TilePlan& plan);
TileSource memory_tile_source(const Mesh& mesh, const TileBuckets& buckets);

// Mesh points with their curvature, in whole-mesh order: a tile's own (phase C's output),
// or those of a box gathered from the tiles it meets.
struct TilePoints {
  std::vector<uint32_t> global;   // ascending
  std::vector<float> positions;   // 3 per point, as in the whole mesh
  std::vector<double> curvature;  // the whole mesh's bits
};

// What phase 1 needs of the tile's own bucket besides its points: the query box (its own
// points, their 1-rings and, with smoothing, the query margin around them) and the bucket's
// triangles, whose corners are the own points' 1-rings (the local-maximum test).
struct TileQuery {
  bool empty = true;  // no point of its own
  BoundingBox query_box;
  std::vector<uint32_t> corners;    // the bucket's corners (whole-mesh numbers), ascending
  std::vector<uint8_t> own;         // per corner
  std::vector<uint32_t> triangles;  // the bucket's, 3 corner numbers each
};

struct TileCurvature {
  TilePoints points;
  TileQuery query;
};

// Phase C: tile t's own points, their curvature and its query, from its bucket alone.
TileCurvature tile_curvature(const TilePlan& plan, size_t t, const TileSource& source);

// Where the tiles' points come from (phase C's outputs, in memory or in files): of tile u,
// the points that may lie in `box` (every one of its points inside it; others allowed: a
// file reads whole zones of a tile), as runs each in whole-mesh order, `ends` receiving
// each run's end. The points are held by the source or read into `scratch`.
using TilePointSource = std::function<const TilePoints&(size_t tile, const BoundingBox& box, TilePoints& scratch,
                                                        std::vector<size_t>& ends)>;
// The source of points held in memory, a tile's whole in one run.
TilePointSource memory_point_source(const std::vector<TilePoints>& points);

// The points inside `box` (margins included) from the tiles it meets, in whole-mesh order.
TilePoints gather_points(const TilePlan& plan, const BoundingBox& box, const TilePointSource& source);

// Phase 0 (fast method), from a tile's own points alone (phase C's): per tile_cell_sigmas()
// sigma, how many occupied cells lie inside the tile's columns (only its points can be
// there) and the keys of those that reach across a face (a neighbour's points may share
// them), ascending. The whole mesh's occupied cells: every tile's inner summed, plus the
// distinct keys among every tile's across (whole_mesh_cells, tile_reduce.h).
struct TileCells {
  std::vector<uint64_t> inner;
  std::vector<std::vector<uint64_t>> across;  // [sigma]
};
TileCells tile_cells(const TilePlan& plan, size_t t, const TilePoints& own);
// A tile's counts added to a process's (its across lists appended: repeats allowed).
void add_tile_cells(TileCells& into, const TileCells& tile);

// A candidate for a local maximum of one scale: an own point whose raw value is above
// every 1-ring neighbour's, with the largest of those (-infinity for an empty ring). The
// test on the normalised values (phase 2, once each scale's maximum M is known) can only
// drop some: x / M rounds monotonically, so value / M > ring_max / M is the same answer as
// value / M > r / M for every neighbour r, as suppress() tests it.
struct MaxCandidate {
  uint32_t vertex;
  double value, ring_max;
};

// Phase 1's result, kept until the tile finishes: per point phase 3 reads (the own points,
// and with smoothing every query point: Sm at own points averages S over them), in
// whole-mesh order.
struct TileRaw {
  std::vector<uint32_t> global;
  std::vector<float> positions;            // 3 per point (with smoothing only)
  std::vector<uint8_t> own;
  std::vector<double> curvature;           // (a driver may drop it: tile_finish then leaves it out)
  std::vector<std::vector<double>> raw;    // [scale][point]
  std::vector<std::vector<MaxCandidate>> candidates;  // [scale], in vertex order
  uint64_t pairs = 0;                      // the sweep's pairs (queries' work)
};

// Phase 1: the raw maps of tile t's query points, over the source points (every point within
// the source margin of its query box) gathered from the tiles that box meets.
TileRaw tile_raw_maps(const TilePlan& plan, size_t t, const TileQuery& query, const TilePointSource& source);

// Each scale's maximum over the mesh points and the lowest vertex attaining it.
struct ScaleMax {
  double max = 0;
  uint32_t vertex = UINT32_MAX;  // none yet
};
std::vector<ScaleMax> tile_scale_max(const TileRaw& tile);
void merge_scale_max(std::vector<ScaleMax>& into, const std::vector<ScaleMax>& from);

// Phase 2: per scale, the own local maxima (vertex, normalised value) in vertex order, from
// the tile's candidates.
struct LocalMax {
  uint32_t vertex;
  double value;
};
std::vector<std::vector<LocalMax>> tile_local_maxima(const std::vector<std::vector<MaxCandidate>>& candidates,
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
