// CPU twin: build_spatial_grid() in src/saliency/spatial_grid.cpp (cell keys and counts)
// meshsal: cell key of every vertex and the count per cell (the counts' prefix sum gives
// the cell starts; the order inside cells comes from the radix sort, grid_radix_*.comp).
// Mirrors build_spatial_grid() (spatial_grid.cpp): points relative to the bbox minimum, in
// double, key = floor(p / cell) clamped. A vertex that is not a mesh point gets the key
// nx*ny*nz, past every cell, so the sort puts it after all mesh points.
#version 450
layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer Pos { dvec4 pos[]; };    // xyz - bbox min, value
layout(std430, binding = 1) readonly buffer Flags { uint is_point[]; };
layout(std430, binding = 2) buffer Count { uint cell_count[]; };
layout(std430, binding = 3) writeonly buffer Key { uint key[]; };
layout(push_constant) uniform Push { uint base; uint n; uint nx; uint ny; uint nz; uint pad; double h; } pc;
void main() {
  uint v = pc.base + gl_GlobalInvocationID.x;
  if (v >= pc.n) return;
  if (is_point[v] == 0u) { key[v] = pc.nx * pc.ny * pc.nz; return; }
  ivec3 c = ivec3(floor(pos[v].xyz / pc.h));
  c = clamp(c, ivec3(0), ivec3(int(pc.nx) - 1, int(pc.ny) - 1, int(pc.nz) - 1));
  uint k = uint(c.x) + pc.nx * (uint(c.y) + pc.ny * uint(c.z));
  key[v] = k;
  atomicAdd(cell_count[k], 1u);
}
