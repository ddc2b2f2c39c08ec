// meshsal public interface: tiles, out of core (meshes larger than memory) and processes
// that share tiles.
// Part of meshsal.h (which includes every part); the conventions at the top of
// meshsal.h hold for every function here.
#pragma once
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "meshsal/mesh.h"
#include "meshsal/saliency.h"
#include "meshsal/simplify.h"

namespace meshsal {

// ------------------------------------------------------------------------------------------
// Processes that share tiles

// Processes that share one tiled saliency computation (SaliencyOptions::tiles), such as
// the ranks of an MPI run: process rank() computes the tiles t with t % ranks() == rank()
// and the processes exchange the few values saliency needs from the whole mesh (each
// scale's maximum and the local maxima behind mbar) and their results through all_gather.
// Every process calls compute_saliency with the same mesh and options and gets the whole
// result. Tiled simplification shares its passes' groups the same way
// (SimplifyOptions::exchange). Out of core (saliency_file, simplify_file) rank 0 builds
// the tiles on disk and the others read them: the temporary folder must be one they all
// reach. The library holds no MPI: the caller implements this over its transport. A step
// only rank 0 runs (reading the input, writing files) tells every process when it fails, so
// all throw its Error; an error that one process alone meets elsewhere leaves the others
// waiting in their next collective unless the transport ends them (the CLI's MPI_Abort).
class TileExchange {
 public:
  virtual ~TileExchange() = default;
  virtual int rank() const = 0;
  virtual int ranks() const = 0;
  // Called by every process in the same order; returns every process's bytes, in rank
  // order (its own included). Throws Error when the transport fails.
  virtual std::vector<std::vector<uint8_t>> all_gather(const std::vector<uint8_t>& mine) = 0;
  // Called by every process in the same order: process `root` gets every process's bytes, in
  // rank order, the others an empty list (the local maxima behind mbar: only one process
  // need hold them all). This default all-gathers; a transport with a rooted gather (MPI's
  // Gatherv) spares the others the memory.
  virtual std::vector<std::vector<uint8_t>> gather(const std::vector<uint8_t>& mine, int root) {
    std::vector<std::vector<uint8_t>> all = all_gather(mine);
    if (rank() != root) all.clear();
    return all;
  }
};

// ------------------------------------------------------------------------------------------
// Out of core: saliency (and, below, simplification) of a mesh file larger than memory

struct OutOfCoreOptions {
  // The process's peak resident memory stays under this many bytes (0: no limit; then
  // SaliencyOptions::tiles decides the tiling). The input is streamed into tiles on disk
  // and the tiles are computed one at a time; the fewest tiles whose largest (with its
  // halo) fits are taken. A limit too small for one tile is an Error naming the smallest
  // workable one.
  uint64_t memory_limit = 0;
  std::string temp_dir;      // where the tiles go ("" = $TMPDIR or /tmp); removed at the end
  bool dump_scales = false;  // also write curvature and saliency_raw_i (as write_saliency_ply)
  // simplify_file only: also write the saliency mesh here as saliency_file() writes it
  // (dump_scales too), from the tiles that weigh the simplification: S computed once. The
  // same bytes with the exact method; the fast method's S is the same to its last bit where
  // both pick the same tiles (the smoothing's wider halo may take more).
  std::string saliency_output;
};

struct OutOfCoreReport {
  uint64_t vertices = 0, points = 0, triangles = 0;
  size_t tiles = 0;               // tiles of the grid
  int ranks = 1;                  // processes that shared them (SaliencyOptions::exchange)
  double eps = 0;
  uint64_t pairs = 0;             // the sweeps' pairs over every tile (halos included)
  uint64_t tile_estimate = 0;     // bytes: the largest tile's estimated peak
  double saliency_min = 0, saliency_max = 0, saliency_mean = 0;  // over the mesh points
  // Their nearest-rank percentiles, as saliency_stats gives them (rank 0's report).
  double saliency_p10 = 0, saliency_p50 = 0, saliency_p90 = 0, saliency_p99 = 0;
  std::vector<StageTime> stages;
};

// Saliency of the mesh in `input` written to `output` as write_saliency_ply() writes it
// (the input's vertex order, positions as read, quality and colours; the same bytes as
// compute_saliency + write_saliency_ply for the exact method), without ever holding the
// whole mesh: binary PLY is streamed (other formats are loaded once and converted to a
// temporary binary PLY). options.method Auto is taken as Fast; tiles run on the CPU.
// With options.exchange, every process passes the same arguments, the temporary folder
// must be on a disk they share, and only rank 0 writes `output`. Before any work, `output`
// must end in .ply (Error "OUTPUT: saliency_file writes a binary PLY: ..." for a .obj or
// .glb name) and pass check_outputs against `input`: it is never the input file, not
// through a symbolic or hard link either.
OutOfCoreReport saliency_file(const std::string& input, const std::string& output,
                              const SaliencyOptions& options, const OutOfCoreOptions& out_of_core);

// simplify_mesh by tiles, for meshes larger than memory (simplify_file runs the same
// passes on disk). options.tiles cubic tiles along the longest axis of the mesh points' bounding
// box, the grid anchored at its minimum; each triangle belongs to the tile of its
// centroid. Rounds, each keeping at most half the faces it starts from: a first pass
// simplifies every tile alone, the vertices it shares with other tiles pinned (neither
// moved nor removed, nor joined by a new edge), every tile down to a common error level
// (the level at which the tiles together keep the round's faces, found from each tile's
// collapse costs); then strip passes: the triangles at the vertices still pinned, plus one
// ring, grouped by grids shifted by 1/2, 1/4 and 3/4 tile, then by tiles twice as large up
// to one piece, simplified with the same pins toward the round's target. The pieces share
// their pinned vertices, so the result has no crack and no border edge the input did not
// have; it is manifold and oriented where the input is. Every pass takes its groups'
// goals from the common level, strips too, so a small piece gives up only what is cheap.
// Open borders simplify as options.lock_border says. Weights apply per vertex as in
// simplify_mesh; each pass starts its quadrics afresh from the surface the last one left.
// Attributes and materials are carried; vertex_origin maps to input vertices, output
// vertices follow their input order. The face count lands at or above the target
// (report.note when above), within 1% where measured. A round whose goal would leave a
// tile fewer than about 1000 output faces takes fewer tiles, so a small target's last
// rounds run in a few large tiles. The RMS error stays near simplify_mesh's (measured
// 0.74-0.86x on igea_134k and bunny_36k at 10% and 1% with 2-8 tiles); it takes 1.5-6x
// simplify_mesh's time (the README's --tiles table; docs/benchmarks.md).
// report.error: the largest collapse error, in units of the whole mesh's diagonal; no
// collapse sequence. tiles 0 or 1, or a target at or above
// the face count: simplify_mesh itself. Throws Error as simplify_mesh does, and for tiles >
// 1024, options.target_error, options.record_collapses or a mesh split at seams
// (Mesh::position_vertex), which the tiled path does not take.
Simplified simplify_mesh_tiled(const Mesh& mesh, const SimplifyOptions& options,
                               const std::vector<double>& vertex_weights = {});

struct OutOfCoreSimplifyReport {
  SimplifyReport simplify;        // faces, collapses, error, note (no vertex_origin, no sequence)
  OutOfCoreReport saliency;       // the saliency the weights came from (tiles 0: no weights)
  unsigned tiles = 0;             // simplification tiles along the longest axis
  double alpha = 0;               // the weights' threshold: weights->alpha_percentile of Sm
  uint64_t tile_estimate = 0;     // bytes: the largest simplification tile's estimated peak
  unsigned groups_at_once = 0;    // a pass's groups simplified side by side: one per thread, as
                                  // many as the limit holds pieces of tile_estimate (at least 1)
  std::vector<StageTime> stages;
};

// Out of core: simplify_mesh_tiled on the mesh in `input` without ever holding it whole,
// written to `output` as a binary PLY (the surviving vertices in input order, an unmoved
// one as read; with weights, S as the per-vertex `quality`, carried as simplify_mesh
// carries attributes). The input is streamed into tiles on disk as saliency_file() does
// (binary PLY; other formats converted once); the saliency (smoothed, method Auto taken as
// Fast) runs a tile at a time, Sm's percentile and mean are found by streaming, and each
// pass of the tiled simplifier reads one group of triangles and its guards at a time.
// weights: the weighting (the Rank curve needs every point's rank and is refused); nullopt:
// plain quadrics. options.tiles: at least this many along the longest axis (0 taken as 1); with a memory limit,
// the fewest that fit it (an Error names the smallest workable limit when none does).
// Writes the bytes that simplify_mesh_tiled with the same tile count, weights from the
// same saliency (S as `quality`) and write_ply give. Positions and S only: other vertex
// properties, materials and seams are not read. Throws Error as simplify_mesh_tiled does,
// and, before any work, for an output as saliency_file() refuses it (not a .ply name, or
// the input file itself, through a link too). out_of_core.saliency_output: the saliency
// mesh too, from the same tiles (even with weights nullopt or a target that keeps the mesh).
// With options.exchange (or saliency_options.exchange; both: the same one) the processes
// share the saliency's tiles and the passes' groups, rank 0 alone writes, and the output
// is the bytes one process writes; rank 0's report is the whole one.
OutOfCoreSimplifyReport simplify_file(const std::string& input, const std::string& output,
                                      const SimplifyOptions& options,
                                      const std::optional<SaliencyWeightOptions>& weights,
                                      const SaliencyOptions& saliency_options, const OutOfCoreOptions& out_of_core);

}  // namespace meshsal
