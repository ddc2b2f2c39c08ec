// CPU twin: the depth buffer of visible_score_cpu() in src/view/visibility.cpp
// meshsal: depth of the mesh for a batch of views. Invocation x of view group y (workgroup
// y: views 4y .. 4y+3) takes triangles x, x + stride, ... and rasterises each into the 4
// views (positions loaded once; few long-lived invocations suit CPU drivers, enough of them
// still fill a GPU); pixels whose centre lies inside or on the triangle get the
// interpolated depth by atomicMin on its bits (non-negative floats order like their bits).
// Same rule as raster_depth() in visibility.cpp. zbuf holds res*res uints per view, cleared
// to +inf (0x7f800000) before.
#version 450
#extension GL_GOOGLE_include_directive : require
layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer Positions { float pos[]; };
layout(std430, binding = 1) readonly buffer Triangles { uint tri[]; };
layout(std430, binding = 2) readonly buffer Views { vec4 rows[]; };
layout(std430, binding = 3) buffer Depth { uint zbuf[]; };
layout(std430, binding = 4) buffer Status { uint over_budget; };
// budget: lavapipe (gallivm) silently ends every loop of an invocation once its loops have
// taken 65535 steps in all; where budget is not 0 an invocation that may reach it says so
// in over_budget (the host then refuses the result instead of returning wrong depths).
layout(push_constant) uniform Push { uint base; uint n; uint res; uint triangles; uint views; uint budget; } pc;
const uint VIEWS_PER_GROUP = 4u;  // views rasterised per invocation (positions loaded once)
#include "view_projection.glsl"

// Returns the loop steps it took (an upper bound: rows + pixels of the box).
uint rasterise(vec3 pa, vec3 pb, vec3 pc_, uint view, int res, float half_res, uint zbase) {
  vec3 a = project_point(pa, view, half_res);
  vec3 b = project_point(pb, view, half_res);
  vec3 c = project_point(pc_, view, half_res);
  precise float area = (b.x - a.x) * (c.y - a.y) - (c.x - a.x) * (b.y - a.y);
  if (!(abs(area) > 1e-12)) return 0u;
  float s = area > 0.0 ? 1.0 : -1.0;
  float inv = 1.0 / abs(area);
  // Pixels whose centre x + 0.5 lies in the bounding box (tiny triangles often have none).
  int x0 = max(0, -int(floor(0.5 - min(a.x, min(b.x, c.x)))));
  int x1 = min(res - 1, int(floor(max(a.x, max(b.x, c.x)) - 0.5)));
  int y0 = max(0, -int(floor(0.5 - min(a.y, min(b.y, c.y)))));
  int y1 = min(res - 1, int(floor(max(a.y, max(b.y, c.y)) - 0.5)));
  for (int y = y0; y <= y1; ++y) {
    float cy = float(y) + 0.5;
    for (int x = x0; x <= x1; ++x) {
      float cx = float(x) + 0.5;
      precise float w0 = s * ((c.x - b.x) * (cy - b.y) - (c.y - b.y) * (cx - b.x));
      precise float w1 = s * ((a.x - c.x) * (cy - c.y) - (a.y - c.y) * (cx - c.x));
      precise float w2 = s * ((b.x - a.x) * (cy - a.y) - (b.y - a.y) * (cx - a.x));
      if (w0 < 0.0 || w1 < 0.0 || w2 < 0.0) continue;
      precise float depth = (w0 * a.z + w1 * b.z + w2 * c.z) * inv;
      uint z = floatBitsToUint(depth);
      uint at = zbase + uint(y * res + x);
      if (z < zbuf[at]) atomicMin(zbuf[at], z);  // most hidden fragments skip the atomic
    }
  }
  uint rows = uint(max(y1 - y0 + 1, 0)), cols = uint(max(x1 - x0 + 1, 0));
  return rows + rows * cols;
}

vec3 load(uint v) { return vec3(pos[3u * v], pos[3u * v + 1u], pos[3u * v + 2u]); }

void main() {
  uint lane = pc.base + gl_GlobalInvocationID.x;
  if (lane >= pc.n) return;
  uint first = gl_WorkGroupID.y * VIEWS_PER_GROUP;
  uint last = min(first + VIEWS_PER_GROUP, pc.views);
  int res = int(pc.res);
  float half_res = 0.5 * float(res);
  float steps_f = 0.0;  // loop steps taken (a float: the sum can pass 2^32)
  for (uint t = lane; t < pc.triangles; t += pc.n) {
    vec3 pa = load(tri[3u * t]), pb = load(tri[3u * t + 1u]), pc_ = load(tri[3u * t + 2u]);
    steps_f += 1.0;
    for (uint view = first; view < last; ++view)
      steps_f += 1.0 + float(rasterise(pa, pb, pc_, view, res, half_res, view * uint(res) * uint(res)));
  }
  if (pc.budget != 0u && steps_f > float(pc.budget)) atomicMax(over_budget, 1u);
}
