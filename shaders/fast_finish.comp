// CPU twin: the end of gaussian_filter_fast() in src/saliency/gaussian_filter_fast.cpp
// meshsal: --method fast, the end of gaussian_filter_fast() for one sigma: G per vertex
// from the summed windows of fast_query.comp. Dense: a lane per piece of a cell
// (fast_aggregate_pieces.comp) extrapolates the sums of the cell's query group linearly
// from the group's centroid to each of the piece's vertices, the centroid's average where
// the extrapolated weight is not positive. Sparse: a lane per sorted mesh point, the vertex's own value where no weight
// reached it (as on the CPU).
#version 450
layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer Sums { double sums[]; };
layout(std430, binding = 1) readonly buffer GroupPos { dvec4 group_pos[]; };  // centroid - min
layout(std430, binding = 2) readonly buffer PieceStart { uint piece_start[]; };
layout(std430, binding = 3) readonly buffer PieceCell { uint piece_cell[]; };
layout(std430, binding = 4) readonly buffer Order { uint order[]; };
layout(std430, binding = 5) readonly buffer Pos { dvec4 pos[]; };  // xyz - min, value
layout(std430, binding = 6) buffer G { double g[]; };              // this sigma, per vertex
layout(std430, binding = 7) readonly buffer CellGroup { uint cell_group[]; };  // dense
layout(push_constant) uniform Push {
  uint base; uint n;  // pieces (dense) or sorted mesh points (sparse)
  uint dense;
  uint offset;        // first entry of g to write (0: each sigma has its own buffer)
  double inv_s2;      // 1 / sigma^2
} pc;
void main() {
  const uint i = pc.base + gl_GlobalInvocationID.x;
  if (i >= pc.n) return;
  if (pc.dense == 0u) {
    const uint v = order[i];
    const double num = sums[2u * i], den = sums[2u * i + 1u];
    g[pc.offset + v] = den > 0.0LF ? num / den : pos[v].w;
    return;
  }
  const uint c = cell_group[piece_cell[i]];
  const uint o = 8u * c;
  const double num0 = sums[o], den0 = sums[o + 1u];
  const dvec3 gn = dvec3(sums[o + 2u], sums[o + 3u], sums[o + 4u]);
  const dvec3 gd = dvec3(sums[o + 5u], sums[o + 6u], sums[o + 7u]);
  const dvec3 q = group_pos[c].xyz;
  const uint b = piece_start[i], e = piece_start[i + 1u];
  for (uint t = b; t < e; ++t) {
    const uint v = order[t];
    precise dvec3 dv = (pos[v].xyz - q) * pc.inv_s2;
    precise double num = num0 + gn.x * dv.x + gn.y * dv.y + gn.z * dv.z;
    precise double den = den0 + gd.x * dv.x + gd.y * dv.y + gd.z * dv.z;
    g[pc.offset + v] = den > 0.0LF ? num / den : num0 / den0;
  }
}
