// CPU twin: referenced_vertices() in src/core/mesh_points.cpp
// meshsal: the mesh-point flags (SPEC 1, "Mesh points") from the triangles already on the
// device: 1 for every vertex a triangle corner names. The buffer is zeroed before; several
// corners may name one vertex at once, hence the atomic (the same 1 either way). A corner
// past the vertices (never, for a validated mesh) marks nothing, as on the host.
#version 450
layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer Corners { uint corners[]; };
layout(std430, binding = 1) buffer Flags { uint flags[]; };
layout(push_constant) uniform Push { uint base; uint n; uint vertices; } pc;
void main() {
  const uint i = pc.base + gl_GlobalInvocationID.x;
  if (i >= pc.n) return;
  const uint v = corners[i];
  if (v < pc.vertices) atomicOr(flags[v], 1u);
}
