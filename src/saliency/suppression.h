// meshsal: Itti-style non-linear suppression of one saliency map (SPEC 1, "Suppression").
#pragma once
#include <cstdint>
#include <vector>

#include "core/adjacency.h"
#include "meshsal/meshsal.h"

namespace meshsal {

struct SuppressionInfo {
  double max = 0;        // maximum of the raw map over mesh points
  double mbar = 0;       // mean of the normalised local maxima other than the global one
  size_t local_maxima = 0;
};

// Returns map / max * (1 - mbar)^2 (zero map stays zero). A local maximum is a mesh point
// strictly greater than each 1-ring neighbour; the global one excluded from mbar is the
// lowest-index mesh point attaining the maximum.
std::vector<double> suppress(const std::vector<double>& map, const std::vector<uint8_t>& is_point,
                             const Adjacency& adjacency, SuppressionInfo* info = nullptr);

// The same, the same bits, with the neighbours taken from the triangles' edges instead of
// the 1-rings (the fast method's: it builds no adjacency). Independent of the thread count.
std::vector<double> suppress_faces(const std::vector<double>& map, const std::vector<uint8_t>& is_point,
                                   const Mesh& mesh, unsigned threads = 0,
                                   SuppressionInfo* info = nullptr);
// The same, the same bits, normalising the map where it lies (8 bytes a vertex less than a
// second array beside it: the fast pipeline's raw maps are not kept).
std::vector<double> suppress_faces(std::vector<double>&& map, const std::vector<uint8_t>& is_point,
                                   const Mesh& mesh, unsigned threads = 0,
                                   SuppressionInfo* info = nullptr);

}  // namespace meshsal
