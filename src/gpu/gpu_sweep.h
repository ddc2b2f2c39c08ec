// meshsal: the parts of the GPU neighbour sweep around its shaders (sweep.glsl): the push
// block, the float copy of the points for the mixed-precision sweep, the check that every
// point was swept, and the double recheck of the near ties a mixed sweep leaves.
#pragma once
#include <cstdint>
#include <vector>

#include "gpu/shader_interfaces.h"
#include "gpu/vk_buffer.h"
#include "gpu/vk_compute.h"

namespace meshsal::gpu {

// sweep.glsl's push block (gpu/shader_interfaces.h).
using SweepPush = shader::SweepPush;

// The sum of the per-point pair counts of a sweep; throws Error when a point has none
// (every point counts itself, so 0 means the sweep never reached it).
uint64_t total_swept_pairs(const std::vector<uint32_t>& pairs);

// sorted_pos32[i] = the float input coordinates and value of sorted_pos[i] (shifted by
// -origin in double).
void make_float_points(vk::Context& ctx, vk::DescriptorPool& pool, const vk::Buffer& sorted_pos,
                       vk::Buffer& sorted_pos32, uint32_t np, const double origin[3]);

// The buffers of one saliency computation that the recheck reads and writes.
struct NearTieBuffers {
  vk::Buffer *raw, *is_point, *bound, *offsets, *neighbors;      // near_tie.comp
  vk::Buffer *sorted_pos, *sorted_vertex, *starts, *params, *pairs, *pos;  // sweep8_list
  // Where the device computed the curvature: its incidence (gpu_curvature.h), whose
  // neighbours near_tie_faces.comp reads in place of offsets and neighbors.
  vk::Buffer *start = nullptr, *entry = nullptr, *order = nullptr, *triangles = nullptr;
};

// After a mixed-precision sweep: sweeps again in double (sweep8_list) every mesh point
// whose value in some raw map is within the two error bounds of a 1-ring neighbour's (from
// the 1-rings, or from the triangles where `b` has the curvature's incidence), and
// overwrites its raw maps, so that the strict local-maximum test falls as in double.
// `push` is the sweep's push block. Returns how many points were swept again.
uint32_t recheck_near_ties(vk::Context& ctx, vk::DescriptorPool& pool, const NearTieBuffers& b,
                           uint32_t nv, uint32_t nmaps, SweepPush push);

// Test hook: a sorted point index the next sweeps leave out of their slice plan (a gap),
// so the check above must catch it; UINT32_MAX (the default) for none.
extern uint32_t test_sweep_gap_at;

// Test hook: when set, recheck_near_ties() only counts the points it would sweep again
// and leaves the mixed-precision maps as they are.
extern bool test_skip_recheck;

}  // namespace meshsal::gpu
