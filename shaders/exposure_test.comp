// CPU twin: exposure_cpu() in src/view/exposure.cpp
// meshsal: exposure of every vertex over a batch of views whose z-buffers
// visibility_raster.comp has just filled. Invocation x takes vertices x, x + stride, ...
// and, for each view of the batch in order, projects the vertex and tests it like
// visibility_test.comp (passes_depth_test() in visibility.h); where it is visible it adds
// the view's score, exposure_weight() in exposure.h with the same float expressions in the
// same order. It writes one float per vertex, the sum over the batch's views; the host adds
// the batches in double and divides by the number of views. Vertices with is_point 0 (no
// triangle uses them) get 0.
// Per view: rows[3v .. 3v+2] the projection rows (shared with the raster), dir[v].xyz the
// unit direction towards the viewer (w unused). `precise` keeps every multiply-add a
// multiply then an add, as the CPU build (-ffp-contract=off) computes them, so that both
// sides make the same visibility decisions.
#version 450
#extension GL_GOOGLE_include_directive : require
layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer Positions { float pos[]; };
layout(std430, binding = 1) readonly buffer Normals { float normal[]; };
layout(std430, binding = 2) readonly buffer Points { float is_point[]; };
layout(std430, binding = 3) readonly buffer Views { vec4 rows[]; };
layout(std430, binding = 4) readonly buffer Directions { vec4 dir[]; };
layout(std430, binding = 5) readonly buffer Depth { uint zbuf[]; };
layout(std430, binding = 6) writeonly buffer Exposure { float exposure[]; };
layout(std430, binding = 7) buffer Status { uint over_budget; };  // see visibility_raster.comp
// facing, centre: which factors apply (ExposureWeighting). two_vx, two_vy: the centre
// bias's 2 vx and 2 vy as the C++ side computes them (2.0f * kCentreVarianceX, ...), so
// that the constants live in one place.
layout(push_constant) uniform Push {
  uint base; uint n; uint res; uint vertices; float tol; uint views; uint budget;
  uint facing; uint centre; float two_vx; float two_vy;
} pc;
#include "view_projection.glsl"
#include "depth_test.glsl"

// exposure_weight(): the score of a visible point p with unit normal n in one view.
float weight(vec3 p, vec3 n, uint view) {
  float s = 1.0;
  if (pc.facing != 0u) {
    vec3 d = dir[view].xyz;
    precise float f = n.x * d.x + n.y * d.y + n.z * d.z;
    s = abs(f);
  }
  if (pc.centre != 0u) {
    vec4 r0 = rows[3u * view], r1 = rows[3u * view + 1u];
    precise float x = r0.x * p.x + r0.y * p.y + r0.z * p.z + r0.w;
    precise float y = r1.x * p.x + r1.y * p.y + r1.z * p.z + r1.w;
    precise float e = -(x * x) / pc.two_vx - (y * y) / pc.two_vy;
    s *= exp(e);
  }
  return s;
}

void main() {
  uint lane = pc.base + gl_GlobalInvocationID.x;
  if (lane >= pc.n) return;
  int res = int(pc.res);
  uint steps = 0u;
  for (uint i = lane; i < pc.vertices; i += pc.n) {
    ++steps;
    float sum = 0.0;
    if (is_point[i] != 0.0) {
      vec3 p = vec3(pos[3u * i], pos[3u * i + 1u], pos[3u * i + 2u]);
      vec3 nrm = vec3(normal[3u * i], normal[3u * i + 1u], normal[3u * i + 2u]);
      for (uint view = 0u; view < pc.views; ++view) {
        ++steps;
        if (visible(p, view, res, steps)) sum += weight(p, nrm, view);
      }
    }
    exposure[i] = sum;
  }
  if (pc.budget != 0u && steps > pc.budget) atomicMax(over_budget, 1u);
}
