// CPU twin: vertex_normals_body() and curvature_sums_body() in src/saliency/curvature.cpp, as
// mean_curvature_morton() runs them
// meshsal: Taubin mean curvature per vertex (SPEC 1) from its triangles in the sorted order
// (curvature_incidence.comp): the area-weighted normal summed triangle by triangle and
// normalised, then for each triangle with three distinct corners its area A twice into the
// area and A k_ij for the vertex's two edges into the sum; H = sum / area (0 without area).
// The same IEEE double operations in the same order as the CPU (`precise`: no fma), so
// the same bits. A vertex with more than MAX_CORNERS triangles (lavapipe ends an
// invocation's loops after 65,535 steps) is left to the host: flagged in counts[slot].
#version 450
#extension GL_GOOGLE_include_directive : require
layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer Pos32 { vec4 pos32[]; };
layout(std430, binding = 1) readonly buffer Triangles { uint tri[]; };
layout(std430, binding = 2) readonly buffer Order { uint order[]; };    // sorted slot -> triangle
layout(std430, binding = 3) readonly buffer Entry { uint entry[]; };    // by vertex: 3 slot + corner
layout(std430, binding = 4) readonly buffer Start { uint start[]; };    // per vertex, + 1
layout(std430, binding = 5) buffer Pos { dvec4 pos[]; };                // w: H
layout(std430, binding = 6) buffer Counts { uint counts[]; };
layout(std430, binding = 7) writeonly buffer H { double h[]; };        // H again, for the host
layout(push_constant) uniform Push { uint base; uint n; uint count_slot; } pc;  // n = vertices; the flag slot
const uint MAX_CORNERS = 16384u;

#include "exact_double.glsl"
dvec3 p(uint v) { return exact_double3(pos32[v].xyz); }

// face_normal(): un-normalised, its length twice the area.
dvec3 face_normal(uint f) {
  precise dvec3 e1 = p(tri[3u * f + 1u]) - p(tri[3u * f]);
  precise dvec3 e2 = p(tri[3u * f + 2u]) - p(tri[3u * f]);
  precise dvec3 fn = dvec3(e1.y * e2.z - e1.z * e2.y, e1.z * e2.x - e1.x * e2.z, e1.x * e2.y - e1.y * e2.x);
  return fn;
}

// edge_term(): k_ij |T_ij|^2, 0 where the edge has zero length or is parallel to N_i.
double edge_term(dvec3 ni, uint i, uint j) {
  precise dvec3 d = p(j) - p(i);
  precise double len2 = d.x * d.x + d.y * d.y + d.z * d.z;
  if (!(len2 > 0.0LF)) return 0.0LF;
  precise double nd = ni.x * d.x + ni.y * d.y + ni.z * d.z;
  precise double tangential2 = len2 - nd * nd;
  if (!(tangential2 > 1e-12LF * len2)) return 0.0LF;
  precise double k = 2.0LF * nd / len2;
  return k;
}

void main() {
  const uint v = pc.base + gl_GlobalInvocationID.x;
  if (v >= pc.n) return;
  const uint b = start[v], e = start[v + 1u];
  if (e - b > MAX_CORNERS) {
    atomicMax(counts[pc.count_slot], e - b);
    pos[v].w = 0.0LF;
    h[v] = 0.0LF;
    return;
  }
  precise dvec3 n = dvec3(0.0LF);
  for (uint j = b; j < e; ++j) n += face_normal(order[entry[j] / 3u]);
  precise double len = sqrt(n.x * n.x + n.y * n.y + n.z * n.z);
  if (len > 0.0LF && !isinf(len) && !isnan(len)) {
    n = dvec3(n.x / len, n.y / len, n.z / len);
  } else {
    n = dvec3(0.0LF);
  }
  precise double sum = 0.0LF, area = 0.0LF;
  for (uint j = b; j < e; ++j) {
    const uint f = order[entry[j] / 3u];
    const uint t0 = tri[3u * f], t1 = tri[3u * f + 1u], t2 = tri[3u * f + 2u];
    if (t0 == t1 || t1 == t2 || t0 == t2) continue;
    const dvec3 fn = face_normal(f);
    precise double A = 0.5LF * sqrt(fn.x * fn.x + fn.y * fn.y + fn.z * fn.z);
    const uint c = entry[j] % 3u;
    const uint t[3] = uint[3](t0, t1, t2);
    area += A + A;
    const double k1 = edge_term(n, v, t[(c + 1u) % 3u]), k2 = edge_term(n, v, t[(c + 2u) % 3u]);
    if (k1 != 0.0LF) sum += A * k1;
    if (k2 != 0.0LF) sum += A * k2;
  }
  const double H = area > 0.0LF ? sum / area : 0.0LF;
  pos[v].w = H;
  h[v] = H;
}
