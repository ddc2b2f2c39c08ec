// CPU twin: the center-surround loop of compute_saliency_cpu() in src/saliency/saliency_cpu.cpp
// meshsal: --method fast, one center-surround map from two sigmas' averages, as
// compute_saliency_cpu() takes it: |G_a - G_b| (or G_a alone when there is no b: the
// smoothed saliency) into output `out`, 0 for vertices that are not mesh points. Each
// sigma's averages are a buffer of their own (one array of all of them passed lavapipe's
// 128 MiB per buffer at 2 million vertices).
#version 450
layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer GA { double ga[]; };  // per vertex
layout(std430, binding = 1) readonly buffer GB { double gb[]; };
layout(std430, binding = 2) readonly buffer Flags { uint is_point[]; };
layout(std430, binding = 3) writeonly buffer Out { double result[]; };  // [output][vertex]
layout(push_constant) uniform Push {
  uint base; uint n;  // vertices
  uint map;           // the output map
  uint has_b;
} pc;
void main() {
  const uint v = pc.base + gl_GlobalInvocationID.x;
  if (v >= pc.n) return;
  const double r = pc.has_b != 0u ? abs(ga[v] - gb[v]) : ga[v];
  result[pc.map * pc.n + v] = is_point[v] != 0u ? r : 0.0LF;
}
