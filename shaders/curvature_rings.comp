// CPU twin: vertex_normals() and mean_curvature() in src/saliency/curvature.cpp, over the
// 1-rings of build_adjacency() in src/core/adjacency.cpp (build_adjacency_reference() its
// oracle)
// meshsal: the exact method's Taubin mean curvature per vertex (SPEC 1) from its triangles
// in input order (gpu_curvature.h's TriangleOrder::input), the 1-rings found on the fly:
// the area-weighted normal summed triangle by triangle and normalised (as curvature.comp);
// then the distinct neighbours in increasing index, each one's edge area the sum, in
// triangle order, of the areas of the triangles with an edge to it (once per such edge, as
// the half-edges of build_adjacency() count them), added to the vertex's area and, times
// k_ij, to its sum; H = sum / area (0 without area). The same IEEE double operations in the
// same order as the CPU (`precise`: no fma), so the same bits. Each neighbour costs a pass
// over the vertex's triangles, so a vertex of more than MAX_CORNERS corners is left to the
// host (mean_curvature_at()): flagged in counts[slot].
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
const uint MAX_CORNERS = 64u;  // at most 16,641 loop steps a vertex: see main()

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
  // vertex_normals(): each corner at v adds its triangle's normal.
  precise dvec3 n = dvec3(0.0LF);
  for (uint j = b; j < e; ++j) n += face_normal(order[entry[j] / 3u]);
  precise double len = sqrt(n.x * n.x + n.y * n.y + n.z * n.z);
  if (len > 0.0LF && !isinf(len) && !isnan(len)) {
    n = dvec3(n.x / len, n.y / len, n.z / len);
  } else {
    n = dvec3(0.0LF);
  }
  // vertex_mean_curvature() over the neighbours in increasing index.
  precise double total_area = 0.0LF, sum = 0.0LF;
  bool have_last = false;
  uint last = 0u;
  // Lavapipe ends an invocation's loops after 65,535 steps in all: the loops over a
  // triangle's corners are written out, so with K corners and N distinct neighbours (at most
  // 2K) a vertex takes K steps for its normal, then N + 1 rounds of the loop below, each one
  // step and K to look for the next neighbour, and K more for each found one's area:
  // K + (N + 1)(K + 1) + N K, at most (2K + 1)^2 = 16,641 for K = 64.
  for (;;) {  // a step per distinct neighbour: `last` only grows
    bool found = false;
    uint next = 0u;
    for (uint j = b; j < e; ++j) {
      const uint f = order[entry[j] / 3u];
      const uint t0 = tri[3u * f], t1 = tri[3u * f + 1u], t2 = tri[3u * f + 2u];
      if (t0 != v && (!have_last || t0 > last) && (!found || t0 < next)) next = t0, found = true;
      if (t1 != v && (!have_last || t1 > last) && (!found || t1 < next)) next = t1, found = true;
      if (t2 != v && (!have_last || t2 > last) && (!found || t2 < next)) next = t2, found = true;
    }
    if (!found) break;
    // The edge area: each triangle once (at its first corner at v), its area once per edge
    // between v and next (a triangle (v, next, next) has two).
    precise double w = 0.0LF;
    for (uint j = b; j < e; ++j) {
      const uint f = order[entry[j] / 3u], c = entry[j] % 3u;
      const uint t0 = tri[3u * f], t1 = tri[3u * f + 1u], t2 = tri[3u * f + 2u];
      if ((c > 0u && t0 == v) || (c > 1u && t1 == v)) continue;
      const uint edges = uint(t0 != t1 && ((t0 == v && t1 == next) || (t0 == next && t1 == v))) +
                         uint(t1 != t2 && ((t1 == v && t2 == next) || (t1 == next && t2 == v))) +
                         uint(t2 != t0 && ((t2 == v && t0 == next) || (t2 == next && t0 == v)));
      if (edges == 0u) continue;
      const dvec3 fn = face_normal(f);
      precise double A = 0.5LF * sqrt(fn.x * fn.x + fn.y * fn.y + fn.z * fn.z);
      w += A;
      if (edges > 1u) w += A;
      if (edges > 2u) w += A;
    }
    total_area += w;
    const double k = edge_term(n, v, next);
    if (k != 0.0LF) sum += w * k;
    last = next;
    have_last = true;
  }
  const double H = total_area > 0.0LF ? sum / total_area : 0.0LF;
  pos[v].w = H;
  h[v] = H;
}
