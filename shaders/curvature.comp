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
const uint MAX_CORNERS = 16384u;
#include "curvature_common.glsl"

void main() {
  const uint v = pc.base + gl_GlobalInvocationID.x;
  if (v >= pc.n) return;
  const uint b = start[v], e = start[v + 1u];
  if (left_to_host(v, b, e, MAX_CORNERS)) return;
  const dvec3 n = vertex_normal(b, e);
  precise double sum = 0.0LF, area = 0.0LF;
  for (uint j = b; j < e; ++j) {
    const uint f = order[entry[j] / 3u];
    const uint t0 = tri[3u * f], t1 = tri[3u * f + 1u], t2 = tri[3u * f + 2u];
    if (t0 == t1 || t1 == t2 || t0 == t2) continue;
    const double A = triangle_area(f);
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
