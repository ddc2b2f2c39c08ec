// CPU twin: suppress() in src/saliency/suppression.cpp (each map's maximum)
// meshsal: second pass of map_max.comp: one work group per scale reduces the partial
// maxima to max_i (suppress(), suppression.cpp).
#version 450
layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer Partial { double partial[]; };
layout(std430, binding = 1) writeonly buffer Max { double map_max[]; };
layout(push_constant) uniform Push { uint base; uint n; uint groups; } pc;
shared double red[64];
void main() {
  uint i = gl_WorkGroupID.x + pc.base / 64u;
  uint t = gl_LocalInvocationID.x;
  double m = 0.0LF;
  for (uint g = t; g < pc.groups; g += 64u) m = max(m, partial[i * pc.groups + g]);
  red[t] = m;
  barrier();
  for (uint off = 32u; off > 0u; off >>= 1u) {
    if (t < off) red[t] = max(red[t], red[t + off]);
    barrier();
  }
  if (t == 0u) map_max[i] = red[0];
}
