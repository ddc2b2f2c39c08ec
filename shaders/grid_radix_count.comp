// CPU twin: the stable sort of build_spatial_grid() in src/saliency/spatial_grid.cpp
// meshsal: one pass of the grid's stable LSD radix sort of (cell key, vertex) pairs, first
// half: invocation t counts the 8-bit digits (key >> shift) & 255 of its tile of TILE
// consecutive items, written digit-major (counts[digit * tiles + t]) so that their
// exclusive prefix sum is where each tile's items of each digit go. Serial tiles keep the
// sort stable without barriers or atomics: equal keys stay in vertex order, as in
// build_spatial_grid() (spatial_grid.cpp), and the cost is linear in the points, however
// many share a cell.
#version 450
layout(local_size_x = 64) in;
layout(constant_id = 0) const uint TILE = 256u;
layout(std430, binding = 0) readonly buffer Key { uint key[]; };
layout(std430, binding = 1) writeonly buffer Count { uint counts[]; };
layout(push_constant) uniform Push { uint base; uint n; uint items; uint shift; uint first; } pc;
void main() {
  uint t = pc.base + gl_GlobalInvocationID.x;  // tile
  if (t >= pc.n) return;
  uint c[256];
  for (uint d = 0u; d < 256u; ++d) c[d] = 0u;
  uint e = min(t * TILE + TILE, pc.items);
  for (uint i = t * TILE; i < e; ++i) c[(key[i] >> pc.shift) & 255u]++;
  for (uint d = 0u; d < 256u; ++d) counts[d * pc.n + t] = c[d];
}
