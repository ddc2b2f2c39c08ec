// CPU twin: visible_score_cpu() in src/view/visibility.cpp
// meshsal: visible score per view. Invocation x of view group y (workgroup y: views
// 4y .. 4y+3) tests vertices x, x + stride, ... against each view's depth like
// test_vertices() in visibility.cpp; the work group adds its 64 sums per view in shared
// memory and writes one value per view and work group, partial[view * (stride / 64) +
// group]; the host adds those few in double (no float atomics).
#version 450
#extension GL_GOOGLE_include_directive : require
layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer Positions { float pos[]; };
layout(std430, binding = 1) readonly buffer Weights { float weight[]; };
layout(std430, binding = 2) readonly buffer Views { vec4 rows[]; };
layout(std430, binding = 3) readonly buffer Depth { uint zbuf[]; };
layout(std430, binding = 4) writeonly buffer Partial { float partial[]; };
layout(std430, binding = 5) buffer Status { uint over_budget; };  // see visibility_raster.comp
layout(push_constant) uniform Push { uint base; uint n; uint res; uint vertices; float tol; uint views; uint budget; } pc;
const uint VIEWS_PER_GROUP = 4u;
shared float sums[VIEWS_PER_GROUP][64];
#include "view_projection.glsl"
#include "depth_test.glsl"

void main() {
  uint lane = pc.base + gl_GlobalInvocationID.x;
  if (lane >= pc.n) return;  // n is a multiple of 64: whole work groups return
  uint first = gl_WorkGroupID.y * VIEWS_PER_GROUP;
  uint count = min(first + VIEWS_PER_GROUP, pc.views) - first;
  int res = int(pc.res);
  // Four named sums (no dynamically indexed array: GPUs would spill it to memory).
  float s0 = 0.0, s1 = 0.0, s2 = 0.0, s3 = 0.0;
  uint steps = 0u;
  for (uint i = lane; i < pc.vertices; i += pc.n) {
    ++steps;
    float w = weight[i];
    if (w == 0.0) continue;
    vec3 q = vec3(pos[3u * i], pos[3u * i + 1u], pos[3u * i + 2u]);
    if (visible(q, first, res, steps)) s0 += w;
    if (count > 1u && visible(q, first + 1u, res, steps)) s1 += w;
    if (count > 2u && visible(q, first + 2u, res, steps)) s2 += w;
    if (count > 3u && visible(q, first + 3u, res, steps)) s3 += w;
  }
  if (pc.budget != 0u && steps > pc.budget) atomicMax(over_budget, 1u);
  uint t = gl_LocalInvocationID.x;
  sums[0][t] = s0;
  sums[1][t] = s1;
  sums[2][t] = s2;
  sums[3][t] = s3;
  barrier();
  for (uint half_ = 32u; half_ > 0u; half_ >>= 1u) {
    if (t < half_)
      for (uint k = 0u; k < VIEWS_PER_GROUP; ++k) sums[k][t] += sums[k][t + half_];
    barrier();
  }
  if (t == 0u) {
    uint groups = pc.n / 64u, group = lane / 64u;
    for (uint k = 0u; k < count; ++k) partial[(first + k) * groups + group] = sums[k][0];
  }
}
