// CPU twin: sweep_cells() in src/saliency/sweep_kernels.inc
// meshsal: --method fast, GPU twin of sweep_cells() (gaussian_filter_fast.cpp): the sums
// sum count*w and sum sum*w over the cell aggregates with |centroid - q| < 2 sigma (strict),
// and in dense mode also their gradients in q (times sigma^2) for the extrapolation to a
// query group's vertices. A lane per query point: a query group's centroid
// (fast_group_centroids.comp; dense) or a mesh point (sparse), in sorted order. As in sweep_layout_rows.glsl, the lanes of a subgroup walk
// the rows of cells around the box of those of the subgroup's query points that lie in
// their own row of cells, so that they load the same candidates at once (lavapipe runs a
// lane per SIMD slot: a gather per lane would cost ~8x); any box holding the lane's own
// point gives it the same sums, so the subgroup size changes nothing but the order of the
// additions. The aggregates are on a uniform grid (gpu_grid.h) and the rows of cells are
// culled against the ball as sweep_point() in sweep.glsl culls them. Lavapipe ends an invocation's loops
// silently after 65,535 steps in all, so a dispatch visits only the candidates whose
// ordinal (in the order the rows are walked) lies in [ord_lo, ord_hi): the host splits a
// query's candidates into windows of at most 32768 and the sums are added up across them.
// The distances, weights and products in float, as the CPU takes them: the centroids and
// the query point (relative to the box minimum, in double here) rounded to float, then the
// same IEEE operations (`precise`: no fma), so that both decide every cutoff and shell
// alike (a cell moved in or out of a sum would show: the sums of a raw map's two scales
// are close); the sums are kept in double.
#version 450
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_GOOGLE_include_directive : require
layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer Sorted { dvec4 sorted_pos[]; };  // centroid - min, sum
layout(std430, binding = 1) readonly buffer SortedCell { uint sorted_cell[]; };
layout(std430, binding = 2) readonly buffer Start { uint starts[]; };
layout(std430, binding = 3) readonly buffer CellCount { double cell_count[]; };
layout(std430, binding = 4) readonly buffer QueryPos { dvec4 query_pos[]; };  // cells or vertices
layout(std430, binding = 5) readonly buffer Order { uint order[]; };  // sorted slot -> vertex
layout(std430, binding = 6) buffer Sums { double sums[]; };  // dense: 8 per cell, sparse: 2 per point
layout(std430, binding = 7) buffer Pairs { uint pairs[]; };
layout(push_constant) uniform Push {
  uint base; uint n;          // queries [base, n)
  uint nx; uint ny; uint nz;  // grid size in cells
  uint dense;                 // 1: query j is cell j with gradients; 0: sorted mesh point j
  uint ord_lo; uint ord_hi;   // the window of candidate ordinals of this dispatch
  double h;                   // grid cell side
  double cut2;                // (2 sigma)^2
  double radius;              // 2 sigma
  double coef;                // 1 / (2 sigma^2)
  double shell2;              // dense: candidates with shell2 <= d^2 < cut2 add shell_w
  double shell_w;             //   to their weight in the gradients (the cutoff's share)
} pc;

// exp_neg_cutoff(): exp(-x) for 0 <= x < 2, as exp_neg_cutoff() in src/core/exp_poly7.h.
#include "exp_poly7.glsl"

void main() {
  const uint gid = gl_GlobalInvocationID.x;
  const uint j = min(pc.base + gid, pc.n - 1u);
  const bool live = pc.base + gid < pc.n;  // a lane past the end only shares the loads
  const uint g0 = pc.base + gid - gid % gl_SubgroupSize;
  const bool dense = pc.dense != 0u;
  const dvec3 q = query_pos[dense ? j : order[j]].xyz;
  const vec3 qf = vec3(q);
  const float cut2f = float(pc.cut2), coeff = float(pc.coef);
  const float shell2f = float(pc.shell2), shell_wf = float(pc.shell_w);
  const double c = pc.h, R = pc.radius, R2 = pc.cut2;
  dvec3 lo = q, hi = q;
  const ivec2 my_row = ivec2(q.yz / c);
  for (uint e = 0u; e < gl_SubgroupSize; ++e) {
    const uint je = min(g0 + e, pc.n - 1u);
    const dvec3 o = query_pos[dense ? je : order[je]].xyz;
    if (ivec2(o.yz / c) == my_row) {
      lo = min(lo, o);
      hi = max(hi, o);
    }
  }
  // A row whose points lie far apart (two crossings of the surface): each lane alone. The
  // host's bound on a walk's candidates counts on a box of at most 2 cells in x.
  if (hi.x - lo.x > 2.0LF * c) {
    lo = q;
    hi = q;
  }
  double num = 0.0LF, den = 0.0LF;
  dvec3 gn = dvec3(0.0LF), gd = dvec3(0.0LF);
  uint count = 0u;
  int zlo = max(0, int(floor((lo.z - R) / c))), zhi = min(int(pc.nz) - 1, int(floor((hi.z + R) / c)));
  int ylo = max(0, int(floor((lo.y - R) / c))), yhi = min(int(pc.ny) - 1, int(floor((hi.y + R) / c)));
  uint ord = 0u;  // candidates of the rows walked so far
  for (int z = zlo; z <= zhi && ord < pc.ord_hi; ++z) {
    double dz = max(0.0LF, max(double(z) * c - hi.z, lo.z - double(z + 1) * c));
    for (int y = ylo; y <= yhi && ord < pc.ord_hi; ++y) {
      double dy = max(0.0LF, max(double(y) * c - hi.y, lo.y - double(y + 1) * c));
      double rest = R2 - dz * dz - dy * dy;
      if (rest <= 0.0LF) continue;
      double hx = sqrt(rest);
      int xa = max(0, int(floor((lo.x - hx) / c)));
      int xb = min(int(pc.nx) - 1, int(floor((hi.x + hx) / c)));
      uint row = pc.nx * (uint(y) + pc.ny * uint(z));
      uint j0 = starts[row + uint(xa)];
      uint len = starts[row + uint(xb) + 1u] - j0;
      // This row's candidates inside the window, as offsets into the row.
      uint a = max(ord, pc.ord_lo) - ord, b = min(ord + len, pc.ord_hi);
      b = b > ord ? b - ord : 0u;
      for (uint t = a; t < b; ++t) {
        const uint k = j0 + t;
        const dvec4 x = sorted_pos[k];
        precise vec3 e = vec3(x.xyz) - qf;
        precise float d2 = e.x * e.x + e.y * e.y + e.z * e.z;
        if (d2 < cut2f) {
          const float sum = float(x.w), cnt = float(cell_count[sorted_cell[k]]);
          precise float w = exp_neg_cutoff_f(d2 * coeff);
          precise float wn = w * sum, wd = w * cnt;
          num += double(wn);
          den += double(wd);
          count += 1u;
          if (dense) {
            // d/dq w(|x - q|) = w (x - q) / sigma^2 (the 1/sigma^2 is applied with dv),
            // and the cutoff's share from the shell (sweep_cells() explains it).
            precise float wg = w + (d2 >= shell2f ? shell_wf : 0.0);
            precise float gwn = wg * sum, gwd = wg * cnt;
            precise vec3 gne = gwn * e, gde = gwd * e;
            gn += dvec3(gne);
            gd += dvec3(gde);
          }
        }
      }
      ord += len;
    }
  }
  if (!live) return;
  if (dense) {
    const uint o = 8u * j;
    sums[o] += num;
    sums[o + 1u] += den;
    sums[o + 2u] += gn.x;
    sums[o + 3u] += gn.y;
    sums[o + 4u] += gn.z;
    sums[o + 5u] += gd.x;
    sums[o + 6u] += gd.y;
    sums[o + 7u] += gd.z;
  } else {
    sums[2u * j] += num;
    sums[2u * j + 1u] += den;
  }
  pairs[j] += count;
}
