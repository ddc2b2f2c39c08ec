// CPU twin: aggregate() in src/saliency/gaussian_filter_fast.cpp (first half)
// meshsal: --method fast, first half of aggregate() (gaussian_filter_fast.cpp): the sums of
// one piece of a cell (at most FAST_PIECE sorted points, so that no invocation loops past
// lavapipe's 65,535 steps however many points share a cell): the input's float
// coordinates summed in double, and the values. fast_aggregate_cells.comp adds the pieces.
#version 450
#extension GL_GOOGLE_include_directive : require
layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer Pos { dvec4 pos[]; };     // value in w
layout(std430, binding = 1) readonly buffer Pos32 { vec4 pos32[]; };  // input coordinates
layout(std430, binding = 2) readonly buffer Order { uint order[]; };  // sorted slot -> vertex
layout(std430, binding = 3) readonly buffer PieceStart { uint piece_start[]; };
layout(std430, binding = 4) writeonly buffer PieceSum { dvec4 piece_sum[]; };
layout(std430, binding = 5) readonly buffer Counts { uint counts[]; };
// n: the pieces' bound the dispatch covers; their count is counts[count_slot] (fast_pieces.comp).
layout(push_constant) uniform Push { uint base; uint n; uint count_slot; } pc;
#include "exact_double.glsl"
void main() {
  uint p = pc.base + gl_GlobalInvocationID.x;
  if (p >= pc.n || p >= counts[pc.count_slot]) return;
  dvec4 s = dvec4(0.0LF);
  const uint b = piece_start[p], e = piece_start[p + 1u];
  for (uint i = b; i < e; ++i) {
    uint v = order[i];
    s += dvec4(exact_double3(pos32[v].xyz), pos[v].w);
  }
  piece_sum[p] = s;
}
