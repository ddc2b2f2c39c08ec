// meshsal: Garland-Heckbert edge-collapse simplification, optionally saliency-weighted
// (SPEC 2; Lee, Varshney, Jacobs 2005, section 4).
#pragma once
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "meshsal/mesh.h"

namespace meshsal {

struct SimplifyOptions {
  // Face count to reach. 0 = use `ratio` instead.
  size_t target_faces = 0;
  // Fraction of the input's (non-degenerate) faces to keep, in (0, 1]; used when
  // target_faces == 0.
  double ratio = 0;
  // Weight of the border-edge quadrics (plane through the border edge, perpendicular to its
  // triangle), times the squared edge length. Larger keeps open borders more exactly.
  double border_weight = 10;
  // A collapse is refused when it turns any remaining triangle's normal by more than
  // acos(min_normal_cos) (fold-over / flip test). 0 = refuse turns of 90 degrees or more.
  double min_normal_cos = 0;
  // Threads for the initial edge costs (0 = all cores); the collapse loop is sequential.
  // The result does not depend on it.
  unsigned threads = 0;
  // Record the sequence of collapses (for tests comparing against simplify_bruteforce).
  bool record_collapses = false;
};

// One edge contraction: vertices `kept` and `removed` (input indices) merge into `kept`,
// which moves to the optimal position. `cost` is the quadric error.
struct Collapse {
  uint32_t kept;
  uint32_t removed;
  double cost;
};

struct SimplifyReport {
  size_t input_faces = 0;     // non-degenerate input triangles (repeated-index ones dropped)
  size_t target_faces = 0;    // the target actually used
  size_t output_faces = 0;
  size_t output_vertices = 0;
  bool reached = false;       // output_faces == target_faces
  std::string note;           // why the target was not reached (empty when it was)
  size_t collapses = 0;
  size_t refused = 0;         // collapses refused (link condition, flips, non-manifold edges)
  double seconds = 0;         // wall time of the whole call: setup, collapse loop, output
  std::vector<Collapse> sequence;      // when options.record_collapses
  std::vector<uint32_t> vertex_origin; // output vertex -> input vertex that survived as it
};

// Simplifies `mesh` to options.target_faces (or ratio * faces) by edge collapses in order of
// quadric error: a priority queue of edge entries with lazy invalidation (a collapse pushes
// the survivor's re-costed edges; entries of changed vertices are skipped or swept out; see
// edge_queue.h).
//  - vertex_weights (may be null): one weight W per input vertex; each vertex quadric is
//    multiplied by W once before any collapse (SPEC 2). Weights add up on collapse through
//    the quadrics (Q_i + Q_j carries W_i Q_i + W_j Q_j); W is not needed separately after.
//    Build W with saliency_weights() (saliency_weights.h). Null = plain quadric method.
//  - Collapses are refused when they break the link condition (would create a non-manifold
//    edge or vertex), touch an edge shared by more than two triangles, join two border
//    vertices across the interior, duplicate a triangle, or flip / fold or degenerate a
//    remaining triangle. Borders are kept by border quadrics.
//  - The result never has fewer faces than the target; it has exactly the target when that
//    is reachable (a closed manifold mesh only has even face counts, and a collapse that
//    would overshoot by one is refused); otherwise report->reached is false and report->note
//    says why.
//  - The output has no unreferenced vertices; vertex order follows the input order of the
//    surviving vertices; positions are float.
// Throws Error on bad input (target 0 or larger than the mesh, ratio outside (0,1], weight
// count not matching the vertex count, negative or non-finite weights).
Mesh simplify_mesh(const Mesh& mesh, const SimplifyOptions& options,
                   const std::vector<double>* vertex_weights = nullptr,
                   SimplifyReport* report = nullptr);

// The test oracle: the same collapses, but every step recomputes the cost and validity of
// every remaining edge and takes the minimum. Both order edges by (cost rounded to float,
// then the internal ids of the two ends: vertices are renumbered along a Morton curve for
// memory locality, identically in both), so with the same input both produce the same
// collapse sequence. O(steps * edges).
Mesh simplify_bruteforce(const Mesh& mesh, const SimplifyOptions& options,
                         const std::vector<double>* vertex_weights = nullptr,
                         SimplifyReport* report = nullptr);

// Target face count from options (target_faces or ratio) for `input_faces` faces, with the
// checks above. Exposed for the CLI and the benchmark.
size_t resolve_target_faces(const SimplifyOptions& options, size_t input_faces);

}  // namespace meshsal
