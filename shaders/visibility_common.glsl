// meshsal: the orthographic projection of camera.h, the same float expressions as
// meshsal::project() so that the GPU path and the CPU twin (visibility.cpp) agree.
// Needs `float pos[]` (x,y,z per vertex) and `vec4 rows[]` (3 per view) declared before.
vec3 project_vertex(uint v, uint view, float half_res) {
  vec4 r0 = rows[3u * view], r1 = rows[3u * view + 1u], r2 = rows[3u * view + 2u];
  float x = pos[3u * v], y = pos[3u * v + 1u], z = pos[3u * v + 2u];
  float nx = r0.x * x + r0.y * y + r0.z * z + r0.w;
  float ny = r1.x * x + r1.y * y + r1.z * z + r1.w;
  float nz = r2.x * x + r2.y * y + r2.z * z + r2.w;
  float d = (1.0 - nz) * 0.5;
  return vec3((nx + 1.0) * half_res, (1.0 - ny) * half_res, d > 0.0 ? d : 0.0);
}
