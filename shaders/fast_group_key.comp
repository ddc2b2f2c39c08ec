// CPU twin: Coarse::key() in src/saliency/query_groups.cpp
// meshsal: --method fast, the query groups on the device, first step: each occupied cell's
// coarse cell, the cell of `factor` cells per axis that holds it ((z/f * gy + y/f) * gx + x/f
// of its key x + dx (y + dy z)); the slots past the cell count (counts[cells_slot]) get
// gx*gy*gz, so that the stable radix sort after it puts them last and keeps the cells of a
// group in ascending order, as group_cells() orders them.
#version 450
layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer CellKey { uint cell_key[]; };
layout(std430, binding = 1) readonly buffer Counts { uint counts[]; };
layout(std430, binding = 2) writeonly buffer Coarse { uint coarse[]; };
layout(push_constant) uniform Push {
  uint base; uint n; uint cells_slot; uint factor;
  uint dx; uint dy; uint gx; uint gy; uint gz;
} pc;
void main() {
  const uint c = pc.base + gl_GlobalInvocationID.x;
  if (c >= pc.n) return;
  if (c >= counts[pc.cells_slot]) {
    coarse[c] = pc.gx * pc.gy * pc.gz;
    return;
  }
  const uint k = cell_key[c];
  const uint x = k % pc.dx, y = k / pc.dx % pc.dy, z = k / pc.dx / pc.dy;
  coarse[c] = ((z / pc.factor) * pc.gy + y / pc.factor) * pc.gx + x / pc.factor;
}
