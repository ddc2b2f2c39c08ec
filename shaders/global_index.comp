// CPU twin: suppress() in src/saliency/suppression.cpp (the global maximum)
// meshsal: per scale, the lowest-index mesh point attaining the maximum: the "global"
// maximum that suppress() (suppression.cpp) leaves out of mbar. One y group row per scale.
#version 450
layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer Raw { double raw[]; };
layout(std430, binding = 1) readonly buffer Flags { uint is_point[]; };
layout(std430, binding = 2) readonly buffer Max { double map_max[]; };
layout(std430, binding = 3) buffer Global { uint global_index[]; };  // starts at ~0u
layout(push_constant) uniform Push { uint base; uint n; } pc;
void main() {
  uint v = pc.base + gl_GlobalInvocationID.x;
  uint i = gl_WorkGroupID.y;
  if (v >= pc.n || is_point[v] == 0u) return;
  double m = map_max[i];
  if (m > 0.0LF && raw[i * pc.n + v] == m) atomicMin(global_index[i], v);
}
