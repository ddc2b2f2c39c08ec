// meshsal: --method fast, GPU twin of sweep_cells() (gaussian_filter_fast.cpp): the sums
// sum count*w and sum sum*w over the cell aggregates with |centroid - q| < 2 sigma (strict),
// and in dense mode also their gradients in q (times sigma^2) for the extrapolation to a
// cell's vertices. A lane per query point: a cell's centroid (dense) or a mesh point
// (sparse); no subgroup operations, so any subgroup size gives the same sums. The
// aggregates are on a uniform grid (gpu_grid.h) and the rows of cells are culled against
// the ball as sweep_point() in sweep.glsl culls them. Lavapipe ends an invocation's loops
// silently after 65,535 steps in all, so a dispatch visits only the candidates whose
// ordinal (in the order the rows are walked) lies in [ord_lo, ord_hi): the host splits a
// query's candidates into windows of at most 32768 and the sums are added up across them.
// All in double: with cells of sigma/6 a cutoff decided by a float distance would move
// whole cells in or out of a sum, and the sums of the two scales of a raw map are close.
#version 450
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
} pc;

// exp(-x) for 0 <= x < 2: exp_neg_cutoff() in gaussian_filter_fast.cpp, (exp(-x/4))^4 with
// a degree-7 Taylor polynomial.
double exp_neg_cutoff(double x) {
  precise double y = x * 0.25LF;
  precise double p = -1.0LF / 5040.0LF;
  p = p * y + 1.0LF / 720.0LF;
  p = p * y + -1.0LF / 120.0LF;
  p = p * y + 1.0LF / 24.0LF;
  p = p * y + -1.0LF / 6.0LF;
  p = p * y + 0.5LF;
  p = p * y + -1.0LF;
  p = p * y + 1.0LF;
  p = p * p;
  return p * p;
}

void main() {
  const uint j = pc.base + gl_GlobalInvocationID.x;
  if (j >= pc.n) return;
  const bool dense = pc.dense != 0u;
  const dvec3 q = query_pos[dense ? j : order[j]].xyz;
  double num = 0.0LF, den = 0.0LF;
  dvec3 gn = dvec3(0.0LF), gd = dvec3(0.0LF);
  uint count = 0u;
  const double c = pc.h, R = pc.radius, R2 = pc.cut2;
  int zlo = max(0, int(floor((q.z - R) / c))), zhi = min(int(pc.nz) - 1, int(floor((q.z + R) / c)));
  int ylo = max(0, int(floor((q.y - R) / c))), yhi = min(int(pc.ny) - 1, int(floor((q.y + R) / c)));
  uint ord = 0u;  // candidates of the rows walked so far
  for (int z = zlo; z <= zhi && ord < pc.ord_hi; ++z) {
    double dz = max(0.0LF, max(double(z) * c - q.z, q.z - double(z + 1) * c));
    for (int y = ylo; y <= yhi && ord < pc.ord_hi; ++y) {
      double dy = max(0.0LF, max(double(y) * c - q.y, q.y - double(y + 1) * c));
      double rest = R2 - dz * dz - dy * dy;
      if (rest <= 0.0LF) continue;
      double hx = sqrt(rest);
      int xa = max(0, int(floor((q.x - hx) / c)));
      int xb = min(int(pc.nx) - 1, int(floor((q.x + hx) / c)));
      uint row = pc.nx * (uint(y) + pc.ny * uint(z));
      uint j0 = starts[row + uint(xa)];
      uint len = starts[row + uint(xb) + 1u] - j0;
      // This row's candidates inside the window, as offsets into the row.
      uint a = max(ord, pc.ord_lo) - ord, b = min(ord + len, pc.ord_hi);
      b = b > ord ? b - ord : 0u;
      for (uint t = a; t < b; ++t) {
        const uint k = j0 + t;
        const dvec4 x = sorted_pos[k];
        precise dvec3 e = x.xyz - q;
        precise double d2 = e.x * e.x + e.y * e.y + e.z * e.z;
        if (d2 < R2) {
          const double w = exp_neg_cutoff(d2 * pc.coef);
          const double wn = w * x.w, wd = w * cell_count[sorted_cell[k]];
          num += wn;
          den += wd;
          count += 1u;
          if (dense) {
            // d/dq w(|x - q|) = w (x - q) / sigma^2; the 1/sigma^2 is applied with dv.
            gn += wn * e;
            gd += wd * e;
          }
        }
      }
      ord += len;
    }
  }
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
