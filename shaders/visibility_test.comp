// meshsal: visible score per view. Invocation x of view y (workgroup y) tests vertices
// x, x + stride, ... against the view's depth like test_vertices() in visibility.cpp and
// writes the sum of the visible weights to partial[view * stride + x]; the host adds the
// partials in double (no barriers, no float atomics).
#version 450
#extension GL_GOOGLE_include_directive : require
layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer Positions { float pos[]; };
layout(std430, binding = 1) readonly buffer Weights { float weight[]; };
layout(std430, binding = 2) readonly buffer Views { vec4 rows[]; };
layout(std430, binding = 3) readonly buffer Depth { uint zbuf[]; };
layout(std430, binding = 4) writeonly buffer Partial { float partial[]; };
layout(push_constant) uniform Push { uint base; uint n; uint res; uint vertices; float tol; } pc;

#include "visibility_common.glsl"

float visible_weight(uint i, uint view, int res, uint zbase) {
  float w = weight[i];
  if (w == 0.0) return 0.0;
  vec3 p = project_vertex(i, view, 0.5 * float(res));
  float fres = float(res);
  if (!(p.x >= 0.0 && p.y >= 0.0 && p.x < fres && p.y < fres)) return 0.0;
  int x = int(p.x), y = int(p.y);
  if (x > res - 1 || y > res - 1) return 0.0;
  float z = uintBitsToFloat(zbuf[zbase + uint(y * res + x)]);
  if (isinf(z)) {
    // Empty pixel (on the silhouette): the nearest surface of the 3x3 around it.
    for (int yy = max(y - 1, 0); yy <= min(y + 1, res - 1); ++yy)
      for (int xx = max(x - 1, 0); xx <= min(x + 1, res - 1); ++xx)
        z = min(z, uintBitsToFloat(zbuf[zbase + uint(yy * res + xx)]));
  }
  return p.z <= z + pc.tol ? w : 0.0;
}

void main() {
  uint lane = pc.base + gl_GlobalInvocationID.x;
  if (lane >= pc.n) return;
  uint view = gl_WorkGroupID.y;
  int res = int(pc.res);
  uint zbase = view * uint(res) * uint(res);
  float sum = 0.0;
  for (uint i = lane; i < pc.vertices; i += pc.n) sum += visible_weight(i, view, res, zbase);
  partial[view * pc.n + lane] = sum;
}
