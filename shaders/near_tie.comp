// CPU twin: sweep_point_default() in src/saliency/sweep_kernels.inc (the double recheck)
// meshsal: marks the mesh points whose raw value in some map is within the sum of the two
// error bounds of a 1-ring neighbour's (the mixed sweep's bounds, sweep.glsl): only for
// those can the strict local-maximum test of suppress() (suppression.cpp) fall otherwise
// than in double, so only they are swept again in double (gpu_near_ties.cpp). The test is
// symmetric, so both ends of a near tie mark themselves.
#version 450
layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer Raw { double raw[]; };  // [map][vertex]
layout(std430, binding = 1) readonly buffer Flags { uint is_point[]; };
layout(std430, binding = 2) readonly buffer Bound { float error_bound[]; };  // [map][vertex]
layout(std430, binding = 3) readonly buffer Offsets { uint offsets[]; };
layout(std430, binding = 4) readonly buffer Neighbors { uint neighbors[]; };
layout(std430, binding = 5) writeonly buffer Need { uint need[]; };
layout(push_constant) uniform Push { uint base; uint n; uint nmaps; } pc;
void main() {
  uint v = pc.base + gl_GlobalInvocationID.x;
  if (v >= pc.n) return;
  bool near = false;
  if (is_point[v] != 0u) {
    for (uint e = offsets[v]; e < offsets[v + 1u]; ++e) {
      uint u = neighbors[e];
      for (uint i = 0u; i < pc.nmaps; ++i) {
        double lim = double(error_bound[i * pc.n + v]) + double(error_bound[i * pc.n + u]);
        near = near || abs(raw[i * pc.n + v] - raw[i * pc.n + u]) <= lim;
      }
    }
  }
  need[v] = near ? 1u : 0u;
}
