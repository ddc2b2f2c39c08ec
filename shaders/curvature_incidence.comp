// CPU twin: the triangle order of mean_curvature_morton() in src/saliency/curvature.cpp
// meshsal: the corners of the triangles in their sorted order (curvature_face_key.comp and
// a stable radix sort): entry 3 s + c is corner c of the triangle at sorted slot s, keyed by
// its vertex for a second stable sort, which gives each vertex its triangles in that order;
// and each vertex's count of corners, whose prefix sum gives where its entries start.
#version 450
layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer Triangles { uint tri[]; };
layout(std430, binding = 1) readonly buffer Order { uint order[]; };   // sorted slot -> triangle
layout(std430, binding = 2) writeonly buffer Key { uint key[]; };      // 3 per slot
layout(std430, binding = 3) buffer Count { uint count[]; };            // per vertex, zeroed
layout(push_constant) uniform Push { uint base; uint n; } pc;          // n = triangles
void main() {
  const uint s = pc.base + gl_GlobalInvocationID.x;
  if (s >= pc.n) return;
  const uint f = order[s];
  for (uint c = 0u; c < 3u; ++c) {
    const uint v = tri[3u * f + c];
    key[3u * s + c] = v;
    atomicAdd(count[v], 1u);
  }
}
