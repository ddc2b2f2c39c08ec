// meshsal: what curvature.comp and curvature_rings.comp share, the CPU's helpers in
// src/saliency/curvature.cpp (face_normal(), edge_term(), vertex_normals_body()): their
// buffers (shader::Curvature and shader::CurvatureRings in gpu/shader_interfaces.h), the
// float coordinates taken into double exactly, and each step in the CPU's IEEE double
// operations and order (`precise`: no fma). Included after `#version` and the local size.
layout(std430, binding = 0) readonly buffer Pos32 { vec4 pos32[]; };
layout(std430, binding = 1) readonly buffer Triangles { uint tri[]; };
layout(std430, binding = 2) readonly buffer Order { uint order[]; };    // sorted slot -> triangle
layout(std430, binding = 3) readonly buffer Entry { uint entry[]; };    // by vertex: 3 slot + corner
layout(std430, binding = 4) readonly buffer Start { uint start[]; };    // per vertex, + 1
layout(std430, binding = 5) buffer Pos { dvec4 pos[]; };                // w: H
layout(std430, binding = 6) buffer Counts { uint counts[]; };
layout(std430, binding = 7) writeonly buffer H { double h[]; };        // H again, for the host
layout(push_constant) uniform Push { uint base; uint n; uint count_slot; } pc;  // n = vertices; the flag slot

#include "exact_double.glsl"
dvec3 p(uint v) { return exact_double3(pos32[v].xyz); }

// face_normal(): un-normalised, its length twice the area.
dvec3 face_normal(uint f) {
  precise dvec3 e1 = p(tri[3u * f + 1u]) - p(tri[3u * f]);
  precise dvec3 e2 = p(tri[3u * f + 2u]) - p(tri[3u * f]);
  precise dvec3 fn = dvec3(e1.y * e2.z - e1.z * e2.y, e1.z * e2.x - e1.x * e2.z, e1.x * e2.y - e1.y * e2.x);
  return fn;
}

// The triangle's area as build_adjacency() takes it.
double triangle_area(uint f) {
  const dvec3 fn = face_normal(f);
  precise double A = 0.5LF * sqrt(fn.x * fn.x + fn.y * fn.y + fn.z * fn.z);
  return A;
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

// vertex_normals_body(): each of the vertex's corners, entries [b, e), adds its triangle's
// normal; the sum normalised, 0 where it vanishes or overflows.
dvec3 vertex_normal(uint b, uint e) {
  precise dvec3 n = dvec3(0.0LF);
  for (uint j = b; j < e; ++j) n += face_normal(order[entry[j] / 3u]);
  precise double len = sqrt(n.x * n.x + n.y * n.y + n.z * n.z);
  if (len > 0.0LF && !isinf(len) && !isnan(len)) {
    n = dvec3(n.x / len, n.y / len, n.z / len);
  } else {
    n = dvec3(0.0LF);
  }
  return n;
}

// A vertex of more than `most` corners (entries [b, e)) is left to the host: its H 0 here,
// its count flagged in counts[count_slot]. True when it is.
bool left_to_host(uint v, uint b, uint e, uint most) {
  if (e - b <= most) return false;
  atomicMax(counts[pc.count_slot], e - b);
  pos[v].w = 0.0LF;
  h[v] = 0.0LF;
  return true;
}
