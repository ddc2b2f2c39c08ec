// CPU twin: morton_order() in src/core/morton_order.cpp and the face keys of
// mean_curvature_morton() in src/saliency/curvature.cpp
// meshsal: the key each triangle is sorted by before the GPU curvature sums its corners'
// terms: the Morton cell (2^5 per axis) of its lowest-coded corner, the corners' codes taken
// as morton_order() takes them (the float position less the box minimum in double, times
// (2^10 - 1) / extent, clamped to [0, 2^10 - 1], truncated, bits interleaved x lowest). A
// stable sort by it gives each vertex its triangles in the order mean_curvature_morton()'s
// renumbered copy visits them, so that the sums are the same bits.
#version 450
#extension GL_GOOGLE_include_directive : require
layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer Pos32 { vec4 pos32[]; };     // input coordinates
layout(std430, binding = 1) readonly buffer Triangles { uint tri[]; };   // 3 per triangle
layout(std430, binding = 2) writeonly buffer Key { uint key[]; };
layout(push_constant) uniform Push {
  uint base; uint n;  // triangles
  uint pad0; uint pad1;
  double minx; double miny; double minz;
  double scalex; double scaley; double scalez;
} pc;

uint spread10(uint x) {  // bit i to bit 3i, for the 10 low bits (spread_bits_21's)
  x &= 0x3ffu;
  x = (x | (x << 16)) & 0x030000ffu;
  x = (x | (x << 8)) & 0x0300f00fu;
  x = (x | (x << 4)) & 0x030c30c3u;
  x = (x | (x << 2)) & 0x09249249u;
  return x;
}

#include "exact_double.glsl"

uint code_of(uint v) {
  const double lo[3] = double[3](pc.minx, pc.miny, pc.minz);
  const double scale[3] = double[3](pc.scalex, pc.scaley, pc.scalez);
  uint code = 0u;
  for (int a = 0; a < 3; ++a) {
    precise double q = (exact_double(pos32[v][a]) - lo[a]) * scale[a];
    const double c = q >= 0.0LF ? min(q, 1023.0LF) : 0.0LF;
    code |= spread10(uint(c)) << uint(a);
  }
  return code;
}

void main() {
  const uint f = pc.base + gl_GlobalInvocationID.x;
  if (f >= pc.n) return;
  const uint c = min(code_of(tri[3u * f]), min(code_of(tri[3u * f + 1u]), code_of(tri[3u * f + 2u])));
  key[f] = c >> 15u;  // 3 * (10 - 5) bits: the cell of 2^5 per axis
}
