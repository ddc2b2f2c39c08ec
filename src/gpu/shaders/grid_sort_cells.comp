// meshsal: orders the points of each cell by vertex index (insertion sort, one thread per
// cell), as build_spatial_grid() (spatial_grid.cpp) has them. The atomic slots of
// grid_key.comp come in any order; without this the sums of the sweep would be added in a
// different order on every run and the results would differ in the last bits.
#version 450
layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer Start { uint starts[]; };
layout(std430, binding = 1) buffer Sorted { dvec4 sorted_pos[]; };
layout(std430, binding = 2) buffer SortedVertex { uint sorted_vertex[]; };
layout(push_constant) uniform Push { uint base; uint n; } pc;  // n = cell count
void main() {
  uint c = pc.base + gl_GlobalInvocationID.x;
  if (c >= pc.n) return;
  uint b = starts[c], e = starts[c + 1u];
  for (uint i = b + 1u; i < e; ++i) {
    uint v = sorted_vertex[i];
    dvec4 p = sorted_pos[i];
    uint j = i;
    while (j > b && sorted_vertex[j - 1u] > v) {
      sorted_vertex[j] = sorted_vertex[j - 1u];
      sorted_pos[j] = sorted_pos[j - 1u];
      --j;
    }
    sorted_vertex[j] = v;
    sorted_pos[j] = p;
  }
}
