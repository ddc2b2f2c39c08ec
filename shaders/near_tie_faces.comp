// CPU twin: sweep_point_default() in src/saliency/sweep_kernels.inc (the double recheck)
// meshsal: near_tie.comp with each vertex's neighbours read from its triangles (the
// incidence the GPU curvature keeps, gpu_curvature.h: no 1-rings built on the host), as
// local_max_faces.comp reads them: the same neighbours, so the same marks. A vertex whose
// triangles times maps would take more loop steps than lavapipe allows an invocation is
// marked without the test: sweeping it again in double is always right, only slower.
#version 450
layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer Raw { double raw[]; };  // [map][vertex]
layout(std430, binding = 1) readonly buffer Flags { uint is_point[]; };
layout(std430, binding = 2) readonly buffer Bound { float error_bound[]; };  // [map][vertex]
layout(std430, binding = 3) readonly buffer Start { uint start[]; };      // per vertex, + 1
layout(std430, binding = 4) readonly buffer Entry { uint entry[]; };      // 3 slot + corner
layout(std430, binding = 5) readonly buffer Order { uint order[]; };      // slot -> triangle
layout(std430, binding = 6) readonly buffer Triangles { uint tri[]; };
layout(std430, binding = 7) writeonly buffer Need { uint need[]; };
layout(push_constant) uniform Push { uint base; uint n; uint nmaps; } pc;
const uint MAX_STEPS = 32768u;  // under lavapipe's 65,535 loop steps an invocation

bool near_tie(uint v, uint u) {
  bool near = false;
  for (uint i = 0u; i < pc.nmaps; ++i) {
    double lim = double(error_bound[i * pc.n + v]) + double(error_bound[i * pc.n + u]);
    near = near || abs(raw[i * pc.n + v] - raw[i * pc.n + u]) <= lim;
  }
  return near;
}

void main() {
  uint v = pc.base + gl_GlobalInvocationID.x;
  if (v >= pc.n) return;
  bool near = false;
  if (is_point[v] != 0u) {
    const uint b = start[v], e = start[v + 1u];
    if ((e - b) * (2u * pc.nmaps + 1u) > MAX_STEPS) {
      near = true;
    } else {
      for (uint j = b; j < e; ++j) {
        const uint f = order[entry[j] / 3u], c = entry[j] % 3u;
        const uint a = tri[3u * f + (c + 1u) % 3u], d = tri[3u * f + (c + 2u) % 3u];
        if (a != v) near = near || near_tie(v, a);
        if (d != v) near = near || near_tie(v, d);
      }
    }
  }
  need[v] = near ? 1u : 0u;
}
