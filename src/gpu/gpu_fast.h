// meshsal: --method fast on a Vulkan device, the GPU twin of gaussian_filter_fast()
// (saliency/gaussian_filter_fast.h), held to it per vertex to 1e-4 of each map's maximum.
// Per sigma: the points sorted into cells of sigma/6 and aggregated (gpu_fast_cells.h), the
// aggregates on a uniform grid (gpu_grid.h), the weighted sums at each dense cell's
// centroid (with gradients, extrapolated to its vertices) or at each point where cells
// are sparse (fast_query.comp), all in double; then the center-surround maps.
#pragma once
#include <cstdint>
#include <vector>

#include "core/mesh_points.h"
#include "meshsal/meshsal.h"
#include "gpu/vk_buffer.h"
#include "gpu/vk_context.h"

namespace meshsal::gpu {

// What to compute: the averages at `sigmas` (model units), then output o =
// |G[out_a[o]] - G[out_b[o]]|, or G[out_a[o]] when out_b[o] < 0 (at most 16 outputs).
struct FastFilterPlan {
  std::vector<double> sigmas;
  std::vector<int> out_a, out_b;
};

// The filter of the values in pos[].w (pos: dvec4 per vertex, position - box.min in
// double; pos32: vec4 per vertex, the input's float coordinates, upload_float_positions();
// flags: uint per vertex, mesh point or not) into result ([output][vertex]
// doubles, 0 on vertices that are not mesh points). np = the mesh points. Returns the
// (query, cell) pairs inside the cutoffs, as FilterStats::pairs counts them on the CPU.
// Throws Error (naming the CPU path) when a scale needs more cells than 32-bit keys hold.
// A query's candidates are walked in windows of ctx.fast_window_candidates, one dispatch each.
uint64_t fast_filter(vk::Context& ctx, const Mesh& mesh, const vk::Buffer& pos,
                     const vk::Buffer& pos32, const vk::Buffer& flags, uint32_t np, const BoundingBox& box,
                     const FastFilterPlan& plan, vk::Buffer& result,
                     const SaliencyOptions& options, const char* stage);

// The float input coordinates per vertex (vec4) on the device: the cells' centroids are
// summed from them, as on the CPU, and the GPU curvature reads them.
vk::Buffer upload_float_positions(vk::Context& ctx, const Mesh& mesh, unsigned threads = 0);
// The same from the positions alone (3 floats a vertex, as Mesh::positions).
vk::Buffer upload_float_positions(vk::Context& ctx, const float* positions, size_t vertex_count, unsigned threads = 0);

// Device bytes fast_filter() needs at its peak besides pos, flags and result.
uint64_t fast_filter_bytes(uint64_t nv, uint64_t np, uint64_t nsig);

}  // namespace meshsal::gpu
