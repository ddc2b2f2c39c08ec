// CPU twin: aggregate() in src/saliency/gaussian_filter_fast.cpp (second half)
// meshsal: --method fast, second half of aggregate() (gaussian_filter_fast.cpp): per cell,
// the sum of its pieces (fast_aggregate_pieces.comp), its centroid rounded to float as the
// CPU rounds it and shifted by the bbox minimum in double (as pos[] holds the points), its
// value sum and its point count; and is_cell[c] = 1 for the cells (counts[count_slot] of
// them), 0 for the slots past them up to n, the bound the dispatch covers (the query grid
// takes the cells as its points by that flag).
#version 450
layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer PieceSum { dvec4 piece_sum[]; };
layout(std430, binding = 1) readonly buffer PieceStart { uint piece_start[]; };
layout(std430, binding = 2) readonly buffer CellPiece { uint cell_piece[]; };  // cells + 1
layout(std430, binding = 3) writeonly buffer CellPos { dvec4 cell_pos[]; };  // centroid - min, sum
layout(std430, binding = 4) writeonly buffer CellCount { double cell_count[]; };
layout(std430, binding = 5) readonly buffer Counts { uint counts[]; };
layout(std430, binding = 6) writeonly buffer IsCell { uint is_cell[]; };
layout(push_constant) uniform Push { uint base; uint n; uint count_slot; uint pad1; double minx; double miny; double minz; } pc;
void main() {
  uint c = pc.base + gl_GlobalInvocationID.x;
  if (c >= pc.n) return;
  const bool cell = c < counts[pc.count_slot];
  is_cell[c] = cell ? 1u : 0u;
  if (!cell) return;
  const uint b = cell_piece[c], e = cell_piece[c + 1u];
  dvec4 s = dvec4(0.0LF);
  for (uint p = b; p < e; ++p) s += piece_sum[p];
  const double count = double(piece_start[e] - piece_start[b]);
  precise dvec3 mean_pos = dvec3(vec3(s.xyz / count));
  precise dvec3 shifted = mean_pos - dvec3(pc.minx, pc.miny, pc.minz);
  cell_pos[c] = dvec4(shifted, s.w);
  cell_count[c] = count;
}
