// meshsal: second half of the counting sort: every mesh point goes to its slot in cell
// order, so that a row of neighbouring cells is one contiguous range in the sweep.
#version 450
layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer Pos { dvec4 pos[]; };
layout(std430, binding = 1) readonly buffer Key { uint key[]; };
layout(std430, binding = 2) readonly buffer Slot { uint slot[]; };
layout(std430, binding = 3) readonly buffer Start { uint starts[]; };
layout(std430, binding = 4) writeonly buffer Sorted { dvec4 sorted_pos[]; };
layout(std430, binding = 5) writeonly buffer SortedVertex { uint sorted_vertex[]; };
layout(push_constant) uniform Push { uint base; uint n; } pc;
void main() {
  uint v = pc.base + gl_GlobalInvocationID.x;
  if (v >= pc.n) return;
  uint k = key[v];
  if (k == 0xffffffffu) return;
  uint j = starts[k] + slot[v];
  sorted_pos[j] = pos[v];
  sorted_vertex[j] = v;
}
