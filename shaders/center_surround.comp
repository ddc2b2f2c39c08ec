// meshsal: raw maps S_i(v) = |G(H, v, s_i) - G(H, v, 2 s_i)| and their maxima over mesh
// points; the GPU twin of the raw-map step of compute_saliency_cpu() (saliency.cpp).
// Maps are >= 0, so the float bits order like the values and atomicMax on them works.
#version 450
layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer Filtered { float filtered[]; };  // [sigma][vertex]
layout(std430, binding = 1) readonly buffer Flags { uint is_point[]; };
layout(std430, binding = 2) readonly buffer Pairs { uint scale_sigma[]; };  // [2i]: s_i, [2i+1]: 2 s_i
layout(std430, binding = 3) writeonly buffer Raw { float raw[]; };         // [scale][vertex]
layout(std430, binding = 4) buffer Max { uint max_bits[]; };               // per scale
layout(push_constant) uniform Push { uint base; uint n; uint nscales; } pc;
shared float red[64];
void main() {
  uint v = pc.base + gl_GlobalInvocationID.x;
  uint t = gl_LocalInvocationID.x;
  bool live = v < pc.n && is_point[v] != 0u;
  for (uint i = 0u; i < pc.nscales; ++i) {
    float s = 0.0;
    if (live) s = abs(filtered[scale_sigma[2u * i] * pc.n + v] - filtered[scale_sigma[2u * i + 1u] * pc.n + v]);
    if (v < pc.n) raw[i * pc.n + v] = s;
    red[t] = s;
    barrier();
    for (uint off = 32u; off > 0u; off >>= 1u) {
      if (t < off) red[t] = max(red[t], red[t + off]);
      barrier();
    }
    if (t == 0u && red[0] > 0.0) atomicMax(max_bits[i], floatBitsToUint(red[0]));
    barrier();
  }
}
