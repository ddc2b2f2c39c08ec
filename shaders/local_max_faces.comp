// CPU twin: suppress_faces_into() in src/saliency/suppression.cpp (the local-maximum test
// over the triangles' edges)
// meshsal: the fast method's local-maximum test, as local_max.comp takes it but with each
// vertex's neighbours read from its triangles (the incidence the GPU curvature keeps,
// gpu_curvature.h: no 1-rings built on the host): a mesh point strictly greater than every
// other corner of every triangle it is in. Each work group writes the sum of its
// normalised local maxima (the global one left out) and their count, per scale.
#version 450
layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer Raw { double raw[]; };
layout(std430, binding = 1) readonly buffer Flags { uint is_point[]; };
layout(std430, binding = 2) readonly buffer Max { double map_max[]; };
layout(std430, binding = 3) readonly buffer Global { uint global_index[]; };
layout(std430, binding = 4) readonly buffer Start { uint start[]; };      // per vertex, + 1
layout(std430, binding = 5) readonly buffer Entry { uint entry[]; };      // 3 slot + corner
layout(std430, binding = 6) readonly buffer Order { uint order[]; };      // slot -> triangle
layout(std430, binding = 7) readonly buffer Triangles { uint tri[]; };
layout(std430, binding = 8) writeonly buffer Partial { dvec2 partial[]; };  // [scale][group]
layout(push_constant) uniform Push { uint base; uint n; uint groups; } pc;
shared dvec2 red[64];
void main() {
  uint v = pc.base + gl_GlobalInvocationID.x;
  uint i = gl_WorkGroupID.y;
  uint t = gl_LocalInvocationID.x;
  double mx = map_max[i];
  dvec2 mine = dvec2(0.0LF);
  if (v < pc.n && is_point[v] != 0u && mx > 0.0LF && v != global_index[i]) {
    double s = raw[i * pc.n + v];
    bool is_max = true;
    for (uint j = start[v]; j < start[v + 1u]; ++j) {
      const uint f = order[entry[j] / 3u], c = entry[j] % 3u;
      const uint a = tri[3u * f + (c + 1u) % 3u], b = tri[3u * f + (c + 2u) % 3u];
      if (a != v) is_max = is_max && s > raw[i * pc.n + a];
      if (b != v) is_max = is_max && s > raw[i * pc.n + b];
    }
    if (is_max) mine = dvec2(s / mx, 1.0LF);
  }
  red[t] = mine;
  barrier();
  for (uint off = 32u; off > 0u; off >>= 1u) {
    if (t < off) red[t] += red[t + off];
    barrier();
  }
  if (t == 0u) partial[i * pc.groups + pc.base / 64u + gl_WorkGroupID.x] = red[0];
}
