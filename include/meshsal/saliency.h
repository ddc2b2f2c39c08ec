// meshsal public interface: saliency (the paper's section 3).
// Part of meshsal.h (which includes every part); the conventions at the top of
// meshsal.h hold for every function here.
#pragma once
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "meshsal/device.h"
#include "meshsal/mesh.h"
#include "meshsal/view.h"

namespace meshsal {

// ------------------------------------------------------------------------------------------
// Saliency (the paper's section 3)

// The GPU sweep's arithmetic. Mixed: distances and weights in float, sums folded into
// doubles, cutoffs decided exactly and near ties of the local-maximum test rechecked in
// double (the default scales; other scales run in double). Double: all in double.
// Auto: mixed on GPUs whose doubles run at most a quarter as fast as floats (consumer GPUs;
// timed once per device by a short probe), double on the others and on CPU devices
// (lavapipe), where the double sweep is the faster one (docs/benchmarks.md). The CPU path
// is always double.
enum class Precision { Auto, Mixed, Double };

// How the Gaussian-weighted averages are taken (SPEC section 5; docs/method.md).
// Exact: over every mesh point within 2 sigma (SPEC section 1), cost ~ n x neighbours.
// Fast: over per-cell aggregates (count, curvature sum, centroid) of cells of sigma/6, a
//   fixed number of cells per vertex whatever the density, so the cost is linear in n;
//   an approximation of Exact, measured against it on the scans (final-saliency
//   correlation and top-30% overlap: docs/method.md, docs/benchmarks.md).
//   Everything after the averages is unchanged; with `smoothed`, Sm uses the same method.
//   Runs on either backend, picked as for Exact; the Vulkan path is held to the CPU's fast
//   path per vertex to 1e-4 of each raw map's maximum (in double on the device).
// Auto: Fast when the exact sweep's estimated pair count (mesh points x mean neighbours
//   within 4 x the largest scale x eps, from 256 sampled points) exceeds kAutoPairBudget,
//   with a one-line notice; else Exact.
enum class Method { Exact, Fast, Auto };
constexpr double kAutoPairBudget = 2e9;  // neighbour pairs (its time: docs/benchmarks.md)

class TileExchange;  // processes that share one tiled computation (tiles.h)

// What S models (docs/method.md, "The perceptual model"; every front end's --model).
// Lee2005: the paper's geometric saliency, SPEC section 1 (the default, exact as ever).
// Perceptual: a prediction of where people look at the rendered object: the exposure of
//   each point over the views of the default elevation band around `up` (occlusion, how
//   squarely it faces the view and how near the view's centre it falls), times
//   1 + height + global rarity + coarse saliency (each cue normalised to [0, 1], equal
//   weights fixed in advance), smoothed on the surface to the size of a human fixation
//   (kFixationSigmaFrac of the diagonal) and scaled to a maximum of 1.
// The cues alone, unsmoothed, each scaled to a maximum of 1:
//   Exposure: the mean over those views of visible x |n.d| (no centre bias);
//   Centre:   the mean over those views of visible x the view's centre bias;
//   Height:   the height along `up`, 0 at the lowest mesh point, 1 at the highest;
//   Rarity:   the self-information -log p of each point's multi-scale curvature
//             descriptor among all the points' (global rarity);
//   Coarse:   the paper's saliency at twice the scales (an octave coarser).
enum class Model { Lee2005, Perceptual, Exposure, Centre, Height, Rarity, Coarse };

// The perceptual model's smoothing: a Gaussian of this fraction of the bounding-box
// diagonal, the size of a human fixation (1.5 degrees of visual angle) when the object's
// bounding sphere fills 30 degrees of the view (docs/method.md).
constexpr double kFixationSigmaFrac = 0.05;

// The most scales SaliencyOptions::scales may hold (every front end's --scales and scales=).
constexpr size_t kMaxScaleCount = 16;

struct SaliencyOptions {
  // Limits (Error otherwise): eps_frac in (0, 0.1], 1..16 scales each in (0, 100], and
  // 2 x largest scale x eps_frac <= 1 (the widest Gaussian at most the bbox diagonal).
  double eps_frac = 0.003;                    // eps = eps_frac * bbox diagonal
  std::vector<double> scales{2, 3, 4, 5, 6};  // s_i = scales[i] * eps
  unsigned threads = 0;                       // CPU threads, 0 = all cores (at most 1024)
  Backend backend = Backend::Cpu;
  int device = -1;                            // Vulkan device index (list_devices), -1 = choose
  // An open Device to run on (may be null; not owned, must outlive the call). With it,
  // Backend::Gpu runs there and Backend::Auto too (falling back to the CPU on failure, as
  // Auto does); `device` is not read and the process's device cache is not used.
  // Backend::Cpu with a session is an Error (the two contradict each other).
  Device* session = nullptr;
  bool smoothed = false;                      // also compute Sm = G(S, 3 eps) (simplification)
  // Keep the raw center-surround maps in SaliencyResult::raw (8 bytes per vertex per
  // scale); false leaves raw empty, and the fast CPU path then holds one map at a time
  // (the CLI asks for them only with --dump-scales). S is the same bits either way.
  bool raw_maps = true;
  Precision precision = Precision::Auto;      // the GPU sweep's arithmetic
  Method method = Method::Exact;              // exact or approximate averages (see Method)
  // Called with a stage name and the fraction done of that stage (0..1), from the calling
  // thread. May be empty.
  std::function<void(const char* stage, double fraction)> progress;
  // Called with a one-line notice (e.g. "auto: no GPU, using the CPU path"). May be empty.
  std::function<void(const std::string&)> notice;
  // Cancellation (may be null): set *cancel from any thread or a signal handler and the
  // call throws Cancelled within a fraction of a second (it polls the flag between chunks
  // of work on every thread, and between GPU submissions). The same in SimplifyOptions,
  // OptimiserOptions and CompareOptions; the flag is only read.
  const std::atomic<bool>* cancel = nullptr;
  // Tiles (0 or 1: none): the mesh points' bounding box is cut into cubes, `tiles` of them
  // along its longest axis; each tile first takes its own points' curvature from its own
  // triangles, then computes its own vertices from the points around them (every mesh
  // point within the largest cutoff of its queries, with its curvature); each scale's
  // maximum and mbar are reduced over all tiles before the suppression. Exact: the same
  // bits as without tiles; Fast: the same to rounding (the order of sums over cells). CPU
  // only (Backend::Gpu with tiles is an Error, Auto takes the CPU). Memory: the mesh,
  // every tile's points and curvature (24 bytes a vertex; under an exchange every
  // process holds every tile's), its raw maps at its own points (about 50 bytes a vertex,
  // more with smoothing) and one tile's work at a time; saliency_file() keeps the mesh,
  // the points and the maps on disk instead.
  unsigned tiles = 0;
  // With tiles: processes sharing the tiles (null: this process computes them all).
  TileExchange* exchange = nullptr;
  // What S models (see Model). The models other than Lee2005 run in memory, in one piece
  // (Error with tiles), and read `up` (the axis the views circle and the height rises
  // along); eps_frac, scales (Coarse: twice each), method, backend and threads hold for
  // them too. On a GPU backend the exposure's z-buffers run on the device.
  Model model = Model::Lee2005;
  UpAxis up = UpAxis::Y;
};

struct StageTime {
  std::string name;
  double seconds;
  // The process's peak resident memory during the stage, in bytes; 0 unless measured
  // (meshsal bench turns it on; reading it restarts the kernel's high-water mark).
  uint64_t peak_bytes = 0;
};

struct SaliencyResult {
  double eps = 0;                         // the scale unit, model units
  std::vector<uint8_t> is_point;          // 1 for mesh points, per vertex
  std::vector<double> curvature;          // mean curvature H per vertex (1/model units)
  std::vector<std::vector<double>> raw;   // raw center-surround maps S_i, [scale][vertex]
  std::vector<double> saliency;           // final saliency S per vertex (0 on non-points)
  std::vector<double> smoothed;           // Sm = G(S, 3 eps) when options.smoothed, else empty
  uint64_t pairs = 0;                     // neighbour pairs the sweep visited (Fast:
                                          // (vertex, cell aggregate) pairs)
  Method method = Method::Exact;          // the method that ran (Auto resolved)
  bool mixed_precision = false;           // the GPU sweep ran in mixed precision
  uint64_t rechecked = 0;                 // points a mixed sweep swept again in double
  std::vector<StageTime> stages;          // wall time per stage
  std::string backend_name;               // "cpu (N threads)" or the Vulkan device name
  size_t tiles = 0;                       // tiles of the grid (SaliencyOptions::tiles), 0: untiled
  int ranks = 1;                          // processes that shared them (TileExchange)
  Model model = Model::Lee2005;           // what `saliency` models (SaliencyOptions::model)
  // The cues of a model other than Lee2005, each per vertex, before they are combined: a
  // cue model's one cue under its name; Perceptual's "exposure_centre" (the exposure seen
  // through the centre bias), "height", "rarity" and "coarse". Empty for Lee2005.
  // write_saliency writes them with dump_scales (as cue_NAME).
  std::vector<std::pair<std::string, std::vector<double>>> cues;
};

// Saliency of every vertex, on options.backend. Throws Error on an invalid mesh or option,
// or (Backend::Gpu) when no Vulkan device can run it; Backend::Auto falls back to the CPU.
SaliencyResult compute_saliency(const Mesh& mesh, const SaliencyOptions& options);

// The same over flat arrays (copied once; see make_mesh).
SaliencyResult compute_saliency(const float* positions, size_t vertex_count,
                                const uint32_t* indices, size_t index_count,
                                const SaliencyOptions& options);

// S over the mesh points of `result` (is_point): how many, min, mean, max and percentiles
// (nearest rank: the smallest value with at least p% of the points at or below it); all 0
// without points. What every front end reports of a saliency run.
struct SaliencyStats {
  size_t points = 0;
  double min = 0, mean = 0, max = 0, p10 = 0, p50 = 0, p90 = 0, p99 = 0;
};
SaliencyStats saliency_stats(const SaliencyResult& result);

// The saliency output of `meshsal saliency`: S of `result` (computed for `mesh`) written
// with the mesh in the format the name gives (write_saliency_ply, write_gltf, write_mesh),
// and with dump_scales its curvature and raw maps beside it (curvature, saliency_raw_0..;
// PLY and glTF keep them).
void write_saliency(const std::string& path, const Mesh& mesh, const SaliencyResult& result, bool dump_scales);

}  // namespace meshsal
