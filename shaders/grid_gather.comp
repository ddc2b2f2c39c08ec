// CPU twin: build_spatial_grid() in src/saliency/spatial_grid.cpp (points in cell order)
// meshsal: last step of the grid build: sorted point j is vertex order[j] (the radix
// sort's values), its position and curvature copied next to its cell's other points, so a
// row of neighbouring cells is one contiguous range in the sweep.
#version 450
layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer Pos { dvec4 pos[]; };
layout(std430, binding = 1) readonly buffer Order { uint order[]; };
layout(std430, binding = 2) writeonly buffer Sorted { dvec4 sorted_pos[]; };
layout(std430, binding = 3) writeonly buffer SortedVertex { uint sorted_vertex[]; };
layout(push_constant) uniform Push { uint base; uint n; } pc;  // n = mesh points
void main() {
  uint j = pc.base + gl_GlobalInvocationID.x;
  if (j >= pc.n) return;
  uint v = order[j];
  sorted_pos[j] = pos[v];
  sorted_vertex[j] = v;
}
