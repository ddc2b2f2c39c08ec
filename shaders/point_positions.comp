// CPU twin: local_points() in src/gpu/gpu_mesh_points.cpp
// meshsal: each vertex's position as the sweeps read it, from the float positions already on
// the device: x, y, z in double less the mesh points' box minimum (the CPU grid's frame;
// one correctly rounded subtraction of exact values, so the same bits as the host's),
// w = 0 (the curvature, which the device writes next).
#version 450
#extension GL_GOOGLE_include_directive : require
layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer Pos32 { vec4 pos32[]; };
layout(std430, binding = 1) writeonly buffer Pos { dvec4 pos[]; };
layout(push_constant) uniform Push { uint base; uint n; uint pad0; uint pad1; double ox; double oy; double oz; } pc;
#include "exact_double.glsl"
void main() {
  const uint v = pc.base + gl_GlobalInvocationID.x;
  if (v >= pc.n) return;
  precise const dvec3 local = exact_double3(pos32[v].xyz) - dvec3(pc.ox, pc.oy, pc.oz);
  pos[v] = dvec4(local, 0.0);
}
