// meshsal: the visibility test of a point in one view (visibility_test, exposure_test), the
// GPU twin of passes_depth_test() in src/view/visibility.h, against the view's z-buffer
// (`zbuf`, res x res uints per view) with tolerance pc.tol, both declared by the includer
// (after view_projection.glsl). steps: the loop steps taken, for lavapipe's budget (see
// visibility_raster.comp).
bool visible(vec3 q, uint view, int res, inout uint steps) {
  vec3 p = project_point(q, view, 0.5 * float(res));
  float fres = float(res);
  if (!(p.x >= 0.0 && p.y >= 0.0 && p.x < fres && p.y < fres)) return false;
  int x = int(p.x), y = int(p.y);
  if (x > res - 1 || y > res - 1) return false;
  uint zbase = view * uint(res) * uint(res);
  float z = uintBitsToFloat(zbuf[zbase + uint(y * res + x)]);
  if (isinf(z)) {
    // Empty pixel (on the silhouette): the nearest surface of the 3x3 around it.
    steps += 12u;
    for (int yy = max(y - 1, 0); yy <= min(y + 1, res - 1); ++yy)
      for (int xx = max(x - 1, 0); xx <= min(x + 1, res - 1); ++xx)
        z = min(z, uintBitsToFloat(zbuf[zbase + uint(yy * res + xx)]));
  }
  return p.z <= z + pc.tol;
}
