// CPU twin: the stable sort of build_spatial_grid() in src/saliency/spatial_grid.cpp
// meshsal: one pass of the grid's stable LSD radix sort, second half: invocation t moves
// the items of its tile, in order, to the places the scanned digit counts give
// (grid_radix_count.comp). In the first pass the values are the item indices themselves
// (the vertex numbers), so no value array has to be filled first.
#version 450
layout(local_size_x = 64) in;
layout(constant_id = 0) const uint TILE = 256u;
layout(std430, binding = 0) readonly buffer KeyIn { uint key_in[]; };
layout(std430, binding = 1) readonly buffer ValueIn { uint value_in[]; };
layout(std430, binding = 2) readonly buffer Offset { uint offsets[]; };
layout(std430, binding = 3) writeonly buffer KeyOut { uint key_out[]; };
layout(std430, binding = 4) writeonly buffer ValueOut { uint value_out[]; };
layout(push_constant) uniform Push { uint base; uint n; uint items; uint shift; uint first; } pc;
void main() {
  uint t = pc.base + gl_GlobalInvocationID.x;  // tile
  if (t >= pc.n) return;
  uint at[256];
  for (uint d = 0u; d < 256u; ++d) at[d] = offsets[d * pc.n + t];
  uint e = min(t * TILE + TILE, pc.items);
  for (uint i = t * TILE; i < e; ++i) {
    uint k = key_in[i];
    uint j = at[(k >> pc.shift) & 255u]++;
    key_out[j] = k;
    value_out[j] = pc.first != 0u ? i : value_in[i];
  }
}
