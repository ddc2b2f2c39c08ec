// meshsal: the view projection of the visibility shaders (visibility_raster, visibility_test,
// exposure_test), the GPU twin of project() in src/view/camera.h: p -> pixel x, y and depth
// by the view's three rows (`rows`, 3 vec4 per view, declared by the includer).
// `precise`: no fused multiply-adds (drivers fuse freely, lavapipe does), so the projection,
// like the rasteriser's weights and depths, is the CPU twin's bits (its build contracts none).
vec3 project_point(vec3 p, uint view, float half_res) {
  vec4 r0 = rows[3u * view], r1 = rows[3u * view + 1u], r2 = rows[3u * view + 2u];
  precise float nx = r0.x * p.x + r0.y * p.y + r0.z * p.z + r0.w;
  precise float ny = r1.x * p.x + r1.y * p.y + r1.z * p.z + r1.w;
  precise float nz = r2.x * p.x + r2.y * p.y + r2.z * p.z + r2.w;
  precise float d = (1.0 - nz) * 0.5;
  return vec3((nx + 1.0) * half_res, (1.0 - ny) * half_res, d > 0.0 ? d : 0.0);
}
