// CPU twin: build_spatial_grid() in src/saliency/spatial_grid.cpp (the sorted points)
// meshsal: the sorted points as floats for the mixed-precision sweep (sweep.glsl): the
// input's own float coordinates (pos + the bbox minimum undoes the shift exactly) and the
// value rounded to float.
#version 450
layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer Sorted { dvec4 sorted_pos[]; };
layout(std430, binding = 1) writeonly buffer Sorted32 { vec4 sorted_pos32[]; };
layout(push_constant) uniform Push { uint base; uint n; uint pad0; uint pad1; double ox; double oy; double oz; } pc;
void main() {
  uint i = pc.base + gl_GlobalInvocationID.x;
  if (i >= pc.n) return;
  dvec4 p = sorted_pos[i];
  sorted_pos32[i] = vec4(vec3(p.xyz + dvec3(pc.ox, pc.oy, pc.oz)), float(p.w));
}
