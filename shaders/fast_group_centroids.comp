// CPU twin: the start of query_cells() in src/saliency/sweep_kernels.inc
// meshsal: --method fast, dense queries: the centroid of each query group (the cells inside
// one cell of FastFilterParams::query_factor cells per axis, saliency/query_groups.h), its
// cells' centroids weighted by their point counts. The queries of fast_query.comp are
// taken there and fast_finish.comp extrapolates from there to the group's vertices.
#version 450
layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer CellPos { dvec4 cell_pos[]; };  // centroid - min
layout(std430, binding = 1) readonly buffer CellCount { double cell_count[]; };
layout(std430, binding = 2) readonly buffer GroupStart { uint group_start[]; };
layout(std430, binding = 3) readonly buffer GroupCell { uint group_cell[]; };
layout(std430, binding = 4) writeonly buffer GroupPos { dvec4 group_pos[]; };  // centroid - min
layout(std430, binding = 5) readonly buffer Counts { uint counts[]; };
// n: the groups' bound the dispatch covers; their count is counts[count_slot] (run_starts.comp).
layout(push_constant) uniform Push { uint base; uint n; uint count_slot; } pc;
void main() {
  const uint g = pc.base + gl_GlobalInvocationID.x;
  if (g >= pc.n || g >= counts[pc.count_slot]) return;
  precise dvec3 q = dvec3(0.0LF);
  precise double n = 0.0LF;
  for (uint i = group_start[g]; i < group_start[g + 1u]; ++i) {
    const uint c = group_cell[i];
    q += cell_count[c] * cell_pos[c].xyz;
    n += cell_count[c];
  }
  group_pos[g] = dvec4(q / n, 0.0LF);
}
