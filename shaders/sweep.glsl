// meshsal: the neighbour sweep, GPU twin of gaussian_filter() (gaussian_filter.cpp).
// One thread per mesh point in cell order (neighbouring threads walk the same cells, so
// lanes stay in step). For each of the (2r+1)^2 rows of cells around the point's cell the
// cells x-r..x+r are one contiguous range of the sorted points. Every candidate adds its
// weight to all sigma sums at once, masked by each sigma's strict cutoff d < 2 s (no
// branches: lavapipe runs 8 lanes of AVX2 and divergent branches cost more than math).
// Included by sweep8.comp (the eight default sigmas with the exp trick of the CPU) and
// sweepn.comp (any sigmas, one exp each).
layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer Sorted { vec4 sorted_pos[]; };  // xyz, value
layout(std430, binding = 1) readonly buffer SortedVertex { uint sorted_vertex[]; };
layout(std430, binding = 2) readonly buffer SortedKey { uint sorted_key[]; };
layout(std430, binding = 3) readonly buffer Start { uint starts[]; };
// params[k] = (2 s_k)^2 (strict cutoff), params[16 + k] = 1 / (2 s_k^2)
layout(std430, binding = 4) readonly buffer Params { float params[]; };
layout(std430, binding = 5) writeonly buffer Filtered { float filtered[]; };  // [sigma][vertex]
layout(std430, binding = 6) writeonly buffer Pairs { uint pairs[]; };         // per sorted point
layout(push_constant) uniform Push {
  uint base; uint n;          // sorted points [base, n) of this submission
  uint nx; uint ny; uint nz;  // grid size in cells
  int r;                      // cell range to visit on each side
  uint stride;                // vertex count (row length of `filtered`)
  uint nsig;                  // number of sigmas (8 in sweep8)
  float inv_2eps2;            // 1 / (2 eps^2), sweep8 only
  float radius2;              // (sweep radius)^2: pairs counted strictly inside
  float ox; float oy; float oz; float inv_h;  // grid origin and 1 / cell side
} pc;

#ifdef FAST8
#define NS 8
#else
#define NS 16
#endif

void main() {
  uint i = pc.base + gl_GlobalInvocationID.x;
  if (i >= pc.n) return;
  vec4 p = sorted_pos[i];
  uint key = sorted_key[i];
  int cx = int(key % pc.nx);
  int cy = int((key / pc.nx) % pc.ny);
  int cz = int(key / (pc.nx * pc.ny));
  float cut2[NS];
  float sw[NS];
  float sh[NS];
  for (int k = 0; k < NS; ++k) {
    cut2[k] = (k < int(pc.nsig)) ? params[k] : -1.0;
    sw[k] = 0.0;
    sh[k] = 0.0;
  }
#ifndef FAST8
  float coef[NS];
  for (int k = 0; k < NS; ++k) coef[k] = (k < int(pc.nsig)) ? params[16 + k] : 0.0;
#endif
  uint count = 0u;
  // Rows and x ranges are culled against the ball around p (as the CPU sweep does), with
  // a small margin: culling only skips work, the strict cutoffs below decide.
  float h = 1.0 / pc.inv_h;
  vec3 o = vec3(pc.ox, pc.oy, pc.oz);
  float R2 = pc.radius2 * 1.0001 + 1e-6 * h * h;
  int x0 = max(cx - pc.r, 0);
  int x1 = min(cx + pc.r, int(pc.nx) - 1);
  for (int z = max(cz - pc.r, 0); z <= min(cz + pc.r, int(pc.nz) - 1); ++z) {
    float zl = o.z + float(z) * h;
    float gz = max(0.0, max(zl - p.z, p.z - (zl + h)));
    for (int y = max(cy - pc.r, 0); y <= min(cy + pc.r, int(pc.ny) - 1); ++y) {
      float yl = o.y + float(y) * h;
      float gy = max(0.0, max(yl - p.y, p.y - (yl + h)));
      float rest = R2 - gy * gy - gz * gz;
      if (rest <= 0.0) continue;
      float xr = sqrt(rest);
      int xa = clamp(int(floor((p.x - xr - o.x) * pc.inv_h)), x0, x1);
      int xb = clamp(int(floor((p.x + xr - o.x) * pc.inv_h)), x0, x1);
      uint row = pc.nx * (uint(y) + pc.ny * uint(z));
      uint j0 = starts[row + uint(xa)];
      uint j1 = starts[row + uint(xb) + 1u];
      for (uint j = j0; j < j1; ++j) {
        vec4 q = sorted_pos[j];
        vec3 d = q.xyz - p.xyz;
        float d2 = dot(d, d);
        count += (d2 < pc.radius2) ? 1u : 0u;
#ifdef FAST8
        // sigmas 2,3,4,5,6,8,10,12 eps: three exps, the rest by squaring (as the CPU does)
        float t = d2 * pc.inv_2eps2;
        float e12 = exp(-t * (1.0 / 144.0));
        float e10 = exp(-t * (1.0 / 100.0));
        float e8 = exp(-t * (1.0 / 64.0));
        float e6 = e12 * e12; e6 *= e6;
        float e3 = e6 * e6; e3 *= e3;
        float e5 = e10 * e10; e5 *= e5;
        float e4 = e8 * e8; e4 *= e4;
        float e2 = e4 * e4; e2 *= e2;
        float e[8] = float[8](e2, e3, e4, e5, e6, e8, e10, e12);
        for (int k = 0; k < 8; ++k) {
          float w = (d2 < cut2[k]) ? e[k] : 0.0;
          sw[k] += w;
          sh[k] += w * q.w;
        }
#else
        for (int k = 0; k < NS; ++k) {
          float w = (d2 < cut2[k]) ? exp(-d2 * coef[k]) : 0.0;
          sw[k] += w;
          sh[k] += w * q.w;
        }
#endif
      }
    }
  }
  uint v = sorted_vertex[i];
  for (int k = 0; k < NS; ++k)
    if (k < int(pc.nsig)) filtered[uint(k) * pc.stride + v] = (sw[k] > 0.0) ? sh[k] / sw[k] : 0.0;
  pairs[i] = count;
}
