// CPU twin: the sum at the end of compute_saliency_cpu() in src/saliency/saliency_cpu.cpp
// meshsal: final saliency S = sum_i S_i / max_i * (1 - mbar_i)^2, the sum at the end of
// compute_saliency_cpu() (saliency_cpu.cpp). Also puts S into pos.w, the value the
// smoothing sweep G(S, 3 eps) filters.
#version 450
layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer Raw { double raw[]; };
layout(std430, binding = 1) readonly buffer Flags { uint is_point[]; };
layout(std430, binding = 2) readonly buffer Factor { double factor[]; };
layout(std430, binding = 3) writeonly buffer Saliency { double saliency[]; };
layout(std430, binding = 4) buffer Pos { dvec4 pos[]; };
layout(push_constant) uniform Push { uint base; uint n; uint nscales; } pc;
void main() {
  uint v = pc.base + gl_GlobalInvocationID.x;
  if (v >= pc.n) return;
  double s = 0.0LF;
  if (is_point[v] != 0u)
    for (uint i = 0u; i < pc.nscales; ++i) s += raw[i * pc.n + v] * factor[i];
  saliency[v] = s;
  pos[v].w = s;
}
