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
const uint MAX_CORNERS = 64u;  // at most 16,641 loop steps a vertex: see main()
#include "curvature_common.glsl"

void main() {
  const uint v = pc.base + gl_GlobalInvocationID.x;
  if (v >= pc.n) return;
  const uint b = start[v], e = start[v + 1u];
  if (left_to_host(v, b, e, MAX_CORNERS)) return;
  const dvec3 n = vertex_normal(b, e);  // vertex_normals()
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
      const double A = triangle_area(f);
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
