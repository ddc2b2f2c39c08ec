// meshsal public interface: simplification (the paper's section 4), its weights, levels of
// detail, comparing two surfaces.
// Part of meshsal.h (which includes every part); the conventions at the top of
// meshsal.h hold for every function here.
#pragma once
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "meshsal/mesh.h"
#include "meshsal/saliency.h"

namespace meshsal {

// ------------------------------------------------------------------------------------------
// Simplification (the paper's section 4)

struct SimplifyOptions {
  size_t target_faces = 0;    // face count to reach; 0 = use `ratio`
  double ratio = 0;           // fraction of the input faces to keep, in (0, 1]
  // Weight of the border-edge quadrics (times the squared edge length). Larger keeps open
  // borders more exactly.
  double border_weight = 10;
  // A collapse is refused when it turns a remaining triangle's normal by more than
  // acos(min_normal_cos). 0 = refuse turns of 90 degrees or more.
  double min_normal_cos = 0;
  unsigned threads = 0;          // threads for the initial edge costs (0 = all cores)
  bool record_collapses = false; // record the collapse sequence (tests)
  // An error bound besides (or instead of) the face target, as meshoptimizer's
  // target_error: a collapse whose error exceeds it is refused, and simplification ends
  // when no collapse within it is left (or the face target is reached). In units of the
  // bounding-box diagonal of the mesh points (0.01 = 1%); 0 = no bound. A collapse's error
  // is the RMS distance of the new vertex to the planes its quadric holds,
  // sqrt(Q(v) / sum of the plane weights), with the unweighted quadrics: vertex weights
  // steer which collapses go first, never what their error reads.
  // With target_error > 0 and neither target_faces nor ratio, the face target is 1.
  double target_error = 0;
  // Vertices on an open border (or a non-manifold edge) are neither moved nor removed:
  // the border keeps its exact vertices and positions.
  bool lock_border = false;
  // simplify_mesh_tiled and simplify_file: cubic tiles along the longest axis (tiles.h);
  // 0 or 1: one tile, the whole mesh. simplify_mesh itself does not tile and refuses more.
  unsigned tiles = 0;
  // simplify_mesh_tiled and simplify_file: processes that share each pass's groups (the
  // ranks of an MPI run; TileExchange in tiles.h). Process r simplifies the groups g with
  // g % ranks == r and every process gets every group's result, so each returns the mesh
  // (simplify_file: rank 0 writes the file) that one process makes: the same bits. Every
  // process passes the same mesh, weights and options. Null: this process alone.
  TileExchange* exchange = nullptr;
  const std::atomic<bool>* cancel = nullptr;  // as SaliencyOptions::cancel
};

// One edge contraction: `removed` merges into `kept` (input indices); `cost` its quadric error.
struct Collapse {
  uint32_t kept;
  uint32_t removed;
  double cost;
};

struct SimplifyReport {
  size_t input_faces = 0;     // non-degenerate input triangles
  size_t target_faces = 0;    // the target actually used
  size_t output_faces = 0;
  size_t output_vertices = 0;
  bool reached = false;       // output_faces == target_faces
  // The target was at or above the mesh's face count (simplify_keeps_mesh): the mesh came
  // back as it was, every vertex and triangle, and `note` says so.
  bool unchanged = false;
  std::string note;           // why the target was not reached, or that the mesh is unchanged
  std::string warning;        // precision_warning(mesh): the input is too coarse to trust
  size_t collapses = 0;
  size_t refused = 0;         // collapses refused (link condition, flips, non-manifold edges)
  double seconds = 0;         // wall time of the whole call
  double error = 0;           // largest error of the collapses made (see target_error)
  std::vector<Collapse> sequence;      // when options.record_collapses
  std::vector<uint32_t> vertex_origin; // output vertex -> the input vertex it survived as
};

// What simplify_mesh (and the other simplifiers) return.
struct Simplified {
  Mesh mesh;              // the simplified mesh, attributes and materials carried
  SimplifyReport report;  // what the simplification did
  double alpha = 0;       // simplify_with_saliency: the weights' alpha (SaliencyWeights); else 0
};

// True when `options` ask for at least `face_count` faces (target_faces >= face_count, or
// no target_faces and ratio 1): simplify_mesh and simplify_with_saliency then return the
// mesh unchanged (SimplifyReport::unchanged, as meshoptimizer does), so that a script over
// meshes of every size does not stop on the small ones. Front ends ask it to skip the
// saliency such a call would not use.
bool simplify_keeps_mesh(const SimplifyOptions& options, size_t face_count);

// Garland-Heckbert edge collapses with area-weighted plane quadrics, border quadrics and
// optimal placement. Mesh::attributes are carried along: the vertex kept by a collapse
// takes the attributes interpolated linearly along the collapsed edge at the new
// position's projection onto it; nx ny nz of moved vertices are renormalised. Vertices
// split at a seam (Mesh::position_vertex) never move or take another side's attributes: a
// collapse onto one keeps it in place, and a seam edge between two positions with one twin
// each side collapses along the seam on both sides at once; so a UV seam stays closed and
// every triangle's texture coordinates come from one side. With lock_border, border
// vertices (seam vertices included) are neither moved nor removed. vertex_weights (empty: none): one weight W >= 0 per input vertex; each
// vertex quadric is multiplied by W once before any collapse (the paper's section 4; build
// W with saliency_weights()). The output is manifold and oriented where the input is, never
// has fewer faces than the target, and has exactly the target when reachable (otherwise
// report.note says why). Output vertices follow the input order of the survivors. A
// target at or above the face count returns the mesh as it is (simplify_keeps_mesh).
// Throws Error on a bad target or weights, and for options.tiles > 1 (simplify_mesh_tiled).
Simplified simplify_mesh(const Mesh& mesh, const SimplifyOptions& options,
                         const std::vector<double>& vertex_weights = {});

// How the smoothed saliency Sm becomes the weights W (docs/method.md, "Weightings").
enum class WeightCurve {
  Threshold,   // the paper: W = lambda Sm if Sm >= alpha, else Sm
  Continuous,  // W = 1 + lambda min(cap, (Sm / alpha)^gamma)   (cap 0: no cap)
  Rank,        // W = 1 + lambda ((r - a) / (1 - a))^gamma where r >= a, else 1; r = the rank
               // of Sm among the mesh points in [0, 1], a = alpha_percentile / 100
               // (gamma 0: a step, 1 + lambda on the top 100 - alpha_percentile %)
};

constexpr double kDefaultWeightFloor = 0.001;

struct SaliencyWeightOptions {
  double lambda = 100;            // amplification of salient vertices, >= 0
  double alpha_percentile = 30;   // alpha = this percentile of Sm over mesh points, [0, 100]
  // Not in the paper: W is raised to at least floor * mean(W) over mesh points, so that no
  // collapse is free. The paper's rule gives W = 0 where Sm is 0 (flat regions), and there
  // every collapse, border ones included, costs nothing, so a flat region can lose its
  // shape (docs/method.md, "Weight floor"). kDefaultWeightFloor, chosen by measurement
  // (docs/method.md, "Weight floor"), removes that and leaves the paper's recipe on the
  // benchmark meshes as it was; 0 gives the literal rule. Where every W is 0 (nothing
  // salient), a floor > 0 makes every W 1: plain quadrics.
  double floor = kDefaultWeightFloor;
  WeightCurve curve = WeightCurve::Threshold;
  double gamma = 1;               // exponent of the Continuous and Rank curves, [0, 16]
  double cap = 0;                 // Continuous: largest (Sm / alpha)^gamma, 0 = no cap
};

// The named weightings of `meshsal simplify --weights`: None (plain quadrics, no weights),
// Saliency (the paper's recipe: SaliencyWeightOptions{} as declared) and Balanced (parameters
// chosen by measurement to keep most of the paper's gain in the salient regions at a
// fraction of its cost in RMS and Hausdorff error: docs/method.md "Weightings",
// docs/benchmarks.md "Simplification"; weight_preset() returns them).
enum class Weighting { None, Saliency, Balanced };

// The weighting a front end uses when none is named (`meshsal simplify` and `batch`
// without --weights, Python's simplify() without weights=): the one place it is decided.
constexpr Weighting kDefaultWeighting = Weighting::Balanced;

// The SaliencyWeightOptions of a named weighting (None: the options are not used).
SaliencyWeightOptions weight_preset(Weighting weighting);

// What saliency_weights returns.
struct SaliencyWeights {
  std::vector<double> weights;  // W per vertex
  double alpha = 0;             // the alpha_percentile of Sm over the mesh points
};

// W(v) for every mesh point (is_point != 0) by options.curve (above); 0 for other vertices.
SaliencyWeights saliency_weights(const std::vector<double>& smoothed, const std::vector<uint8_t>& is_point,
                                 const SaliencyWeightOptions& options);

// Smoothed saliency Sm = G(S, 3 eps) over the mesh points, eps = eps_frac * bbox diagonal,
// with the exact averages.
std::vector<double> smooth_saliency(const Mesh& mesh, const std::vector<double>& saliency,
                                    double eps_frac = 0.003, unsigned threads = 0);

// The same with the averages of options.method (Exact, Fast, or Auto decided as
// compute_saliency decides it on this mesh), eps_frac, threads and cancel: the method these
// options name, not necessarily the one that computed `saliency` (nothing records that).
// Given the options that computed S, the result is compute_saliency's own Sm
// (SaliencyOptions::smoothed) up to the backend's rounding. On the CPU, whatever
// options.backend says: on a large scan the fast CPU filter takes a fraction of the exact
// one's time, which can be most of a simplification's (docs/benchmarks.md).
std::vector<double> smooth_saliency(const Mesh& mesh, const std::vector<double>& saliency,
                                    const SaliencyOptions& options);

// What simplification_weights() returns.
struct SimplificationWeights {
  std::vector<double> weights;   // W per vertex (0 on vertices no triangle uses)
  double alpha = 0;              // the alpha_percentile of Sm over the mesh points
  std::vector<double> saliency;  // S per vertex: computed, or the one given
  std::string device;            // what computed S (SaliencyResult::backend_name: "cpu (N
                                 // threads)" or the Vulkan device's name); empty when S was given
};

// The per-vertex weights W of saliency-guided simplification: saliency (computed with
// `saliency_options`, or taken from `saliency` when it is not empty: one S per vertex),
// smoothed to Sm = G(S, 3 eps) with saliency_options.method (smooth_saliency), then
// saliency_weights(). A mesh split at seams (Mesh::position_vertex) is weighed welded (the
// twins get their position's values). Every front end (simplify, batch, Python) calls this.
SimplificationWeights simplification_weights(const Mesh& mesh, const SaliencyWeightOptions& weight_options,
                                             const SaliencyOptions& saliency_options,
                                             const std::vector<double>& saliency = {});

// Saliency-guided simplification in one call: saliency (computed with `saliency_options`,
// or taken from `saliency` when it is not empty: one S per vertex), smoothed, turned into
// weights and used by simplify_mesh; Simplified::alpha is the weights' alpha.
Simplified simplify_with_saliency(const Mesh& mesh, const SimplifyOptions& options,
                                  const SaliencyWeightOptions& weight_options,
                                  const SaliencyOptions& saliency_options,
                                  const std::vector<double>& saliency = {});

// The most levels one chain of levels of detail may have (simplify_lod, --lod, lod=).
constexpr size_t kMaxLodLevels = 16;

// One level of a chain of levels of detail (simplify_lod).
struct LodLevel {
  Mesh mesh;                     // the level, attributes and materials carried
  std::vector<double> saliency;  // S per vertex of this level (the input's, carried); empty unweighted
  SimplifyReport report;         // of the step that made it from the level before
};

// Levels of detail in one call: each level's face target from `levels` (target_faces, or
// ratio of the INPUT's faces; lock_border and the rest as simplify_mesh reads them; no
// target_error), as parse_lod_levels would read them: all counts or all ratios, each below
// the one before (Error otherwise). A level at or above the faces of the level it starts
// from is that level unchanged (report.unchanged), as simplify_mesh leaves a mesh whose
// face count is at or below the target. With weight_options, the
// saliency is computed once on `mesh` (saliency_options; or taken from `saliency`) and
// carried down the chain as a vertex attribute, interpolated along each collapse; each
// level is simplified from the level before with weights from S on that mesh
// (simplification_weights). Without (nullopt), plain quadrics. Simplifying from the level
// before measured better than from the input at equal faces (README, "Levels of detail in
// one run"; docs/benchmarks.md).
std::vector<LodLevel> simplify_lod(const Mesh& mesh, const std::vector<SimplifyOptions>& levels,
                                   const std::optional<SaliencyWeightOptions>& weight_options,
                                   const SaliencyOptions& saliency_options, const std::vector<double>& saliency = {});

// Writes a chain: a .glb or .gltf holds `mesh` (with its saliency, may be empty) as LOD0 and
// each level as LOD1.. (write_gltf: one mesh each, linked by MSFT_lod); an .obj or .ply
// path gets one file per level, lod_level_path(path, 1..) (a PLY with the level's S as
// `quality`), and `mesh` is not written.
void write_lod(const std::string& path, const Mesh& mesh, const std::vector<double>& saliency,
               const std::vector<LodLevel>& levels);
// "dir/out_lod2.obj" for ("dir/out.obj", 2): the file of level `level` of write_lod.
std::string lod_level_path(const std::string& path, size_t level);

// ------------------------------------------------------------------------------------------
// Comparing two surfaces

struct CompareOptions {
  size_t face_samples = 200000;     // area samples per surface, on top of its vertices
  double salient_fraction = 0.30;   // top fraction of the original's mesh points by saliency
  unsigned threads = 0;             // 0 = all cores
  const std::atomic<bool>* cancel = nullptr;  // as SaliencyOptions::cancel
};

// Distances in model units (divide by `diagonal` for a share of the model's size).
struct SurfaceComparison {
  double diagonal = 0;          // bbox diagonal of the original's mesh points
  double forward_max = 0;       // original's samples -> simplified surface
  double forward_rms = 0;
  double backward_max = 0;      // simplified's samples -> original surface
  double backward_rms = 0;
  double hausdorff = 0;         // max(forward_max, backward_max)
  double rms = 0;               // max(forward_rms, backward_rms)
  double salient_error = -1;    // mean distance of the salient vertices; -1 without saliency
  size_t salient_vertices = 0;
  size_t forward_samples = 0, backward_samples = 0;
};

// Point-to-surface distances both ways (BVH). `saliency` (empty: none): one value per vertex
// of the original; its top salient_fraction of mesh points give salient_error.
SurfaceComparison compare_surfaces(const Mesh& original, const Mesh& simplified,
                                   const std::vector<double>& saliency,
                                   const CompareOptions& options = {});

}  // namespace meshsal
