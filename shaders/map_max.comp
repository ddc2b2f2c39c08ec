// CPU twin: suppress() in src/saliency/suppression.cpp (each map's maximum)
// meshsal: maximum of each raw map over the mesh points (the "max" of suppress(),
// suppression.cpp), first pass: one partial maximum per work group and scale (y).
#version 450
layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer Raw { double raw[]; };      // [scale][vertex]
layout(std430, binding = 1) readonly buffer Flags { uint is_point[]; };
layout(std430, binding = 2) writeonly buffer Partial { double partial[]; };  // [scale][group]
layout(push_constant) uniform Push { uint base; uint n; uint groups; } pc;
shared double red[64];
void main() {
  uint v = pc.base + gl_GlobalInvocationID.x;
  uint i = gl_WorkGroupID.y;
  uint t = gl_LocalInvocationID.x;
  red[t] = (v < pc.n && is_point[v] != 0u) ? raw[i * pc.n + v] : 0.0LF;
  barrier();
  for (uint off = 32u; off > 0u; off >>= 1u) {
    if (t < off) red[t] = max(red[t], red[t + off]);
    barrier();
  }
  if (t == 0u) partial[i * pc.groups + pc.base / 64u + gl_WorkGroupID.x] = red[0];
}
