// meshsal: Garland-Heckbert edge-collapse simplification, optionally saliency-weighted
// (SPEC 2; Lee, Varshney, Jacobs 2005, section 4).
#pragma once
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "meshsal/meshsal.h"

namespace meshsal {

// The test oracle: the same collapses, but every step recomputes the cost and validity of
// every remaining edge and takes the minimum. Both order edges by (cost rounded to float,
// then the internal ids of the two ends: vertices are renumbered along a Morton curve for
// memory locality, identically in both), so with the same input both produce the same
// collapse sequence. O(steps * edges). It shares the cost, check and collapse code with
// simplify_mesh, so it only catches ordering bugs; the collapse check has its own oracle
// (tests/simplify/test_simplify_check_oracle.cpp).
Mesh simplify_bruteforce(const Mesh& mesh, const SimplifyOptions& options,
                         const std::vector<double>* vertex_weights = nullptr,
                         SimplifyReport* report = nullptr);

// simplify_mesh with the vertices flagged in `pinned` (one flag per vertex; null = none)
// kept in place as lock_border keeps border vertices: no collapse moves or removes them.
// The tiled simplifier pins the vertices its cuts share with other tiles (simplify_tiled.cpp).
Mesh simplify_pinned(const Mesh& mesh, const SimplifyOptions& options, const std::vector<double>* vertex_weights,
                     const std::vector<uint8_t>* pinned, SimplifyReport* report);

// Target face count from options (target_faces or ratio) for `input_faces` faces, with the
// checks above. Exposed for the CLI and the benchmark.
size_t resolve_target_faces(const SimplifyOptions& options, size_t input_faces);

}  // namespace meshsal
