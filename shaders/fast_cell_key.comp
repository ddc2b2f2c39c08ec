// CPU twin: cell_key() in src/saliency/sparse_cells.cpp
// meshsal: --method fast, GPU twin of cell_key() in src/saliency/sparse_cells.cpp: the cell
// of edge `cell` that each mesh point falls in, as the dense index x + nx (y + ny z) with
// nx, ny, nz the cells per axis (plan_fast_grid() counts them as cell_dims() does), the
// same number as the CPU's key (z * dims[1] + y) * dims[0] + x, computed from the same
// doubles (position - bbox min) divided the same way; here it must fit 32 bits
// (plan_fast_grid() checks). A vertex that is not a mesh point gets nx*ny*nz, past every
// cell, so the radix sort puts it after all mesh points.
#version 450
layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer Pos { dvec4 pos[]; };  // xyz - bbox min, value
layout(std430, binding = 1) readonly buffer Flags { uint is_point[]; };
layout(std430, binding = 2) writeonly buffer Key { uint key[]; };
layout(push_constant) uniform Push { uint base; uint n; uint nx; uint ny; uint nz; uint pad; double cell; } pc;
void main() {
  uint v = pc.base + gl_GlobalInvocationID.x;
  if (v >= pc.n) return;
  if (is_point[v] == 0u) {
    key[v] = pc.nx * pc.ny * pc.nz;
    return;
  }
  precise dvec3 q = pos[v].xyz / pc.cell;
  uvec3 c = min(uvec3(q), uvec3(pc.nx - 1u, pc.ny - 1u, pc.nz - 1u));
  key[v] = c.x + pc.nx * (c.y + pc.ny * c.z);
}
