// meshsal: --method fast, the center-surround maps from the averages, as
// compute_saliency_cpu() takes them: output o is |G[a] - G[b]| (or G[a] alone when there is
// no b: the smoothed saliency), 0 for vertices that are not mesh points.
#version 450
layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer G { double g[]; };  // [sigma][vertex]
layout(std430, binding = 1) readonly buffer Flags { uint is_point[]; };
layout(std430, binding = 2) writeonly buffer Out { double result[]; };  // [output][vertex]
layout(push_constant) uniform Push {
  uint base; uint n;  // vertices
  uint nout;
  uint pad;
  uint ab[16];        // output o: a | (b + 1) << 16, b + 1 = 0 for none
} pc;
void main() {
  const uint v = pc.base + gl_GlobalInvocationID.x;
  if (v >= pc.n) return;
  const bool point = is_point[v] != 0u;
  for (uint o = 0u; o < pc.nout; ++o) {
    const uint a = pc.ab[o] & 0xffffu, b1 = pc.ab[o] >> 16;
    const double ga = g[a * pc.n + v];
    const double r = b1 == 0u ? ga : abs(ga - g[(b1 - 1u) * pc.n + v]);
    result[o * pc.n + v] = point ? r : 0.0LF;
  }
}
