// meshsal: the neighbour sweep, GPU twin of gaussian_filter() / sweep_point()
// (gaussian_filter.cpp), in double like the CPU so that near-ties in the local-maximum
// test fall the same way. One subgroup per mesh point, in cell order: like the CPU's
// 4-wide loop, the lanes split the candidates of a row between them. Rows of cells are culled against the ball
// as on the CPU; the cells of a row are one contiguous range of the sorted points. Every
// candidate adds its weight to all sigma sums at once, masked by each sigma's strict
// cutoff d < 2 s (no branches: lavapipe runs 8 lanes of AVX2). Weights of a sigma half of
// another are w(s) = w(2s)^4, as in the CPU's KernelPlan. The center-surround step
// S_i = |G(s_i) - G(2 s_i)| is done here too, so only the raw maps are written.
// Included by sweep8.comp (the default sigmas 12,10,8,6,5,4,3,2 eps, fixed plan) and
// sweepn.comp (any plan of up to 16 sigmas, specialised per plan).
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_arithmetic : require
layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer Sorted { dvec4 sorted_pos[]; };  // xyz, value
layout(std430, binding = 1) readonly buffer SortedVertex { uint sorted_vertex[]; };
layout(std430, binding = 2) readonly buffer Start { uint starts[]; };
// The plan, largest sigma first: cut2 = (2 s)^2, coef = 1 / (2 s^2), parent = index of 2 s
// or -1; output i is |G[out_a] - G[out_b]|, or G[out_a] when out_b < 0.
layout(std430, binding = 3) readonly buffer Params {
  double cut2[16]; double coef[16]; int parent[16]; int out_a[16]; int out_b[16];
};
layout(std430, binding = 4) writeonly buffer Out { double result[]; };  // [output][vertex]
layout(std430, binding = 5) writeonly buffer Pairs { uint pairs[]; };   // per sorted point
layout(push_constant) uniform Push {
  uint base; uint n;          // sorted points [base, n) of this submission
  uint nx; uint ny; uint nz;  // grid size in cells
  int pad0;
  uint stride;                // vertex count (row length of `result`)
  uint nsig;                  // sigmas in the plan (8 in sweep8)
  uint nout;                  // outputs
  uint pad;
  double h;                   // cell side
  double radius2;             // largest cutoff^2: pairs are counted strictly inside
} pc;

#ifdef FAST8
#define NS 8
#else
// sweepn is specialised per plan: the sigma count and each sigma's parent are constants
// to the driver, so the loops unroll to exactly the plan's exps and squarings.
layout(constant_id = 0) const int NS = 16;
layout(constant_id = 1) const int P0 = -1;
layout(constant_id = 2) const int P1 = -1;
layout(constant_id = 3) const int P2 = -1;
layout(constant_id = 4) const int P3 = -1;
layout(constant_id = 5) const int P4 = -1;
layout(constant_id = 6) const int P5 = -1;
layout(constant_id = 7) const int P6 = -1;
layout(constant_id = 8) const int P7 = -1;
layout(constant_id = 9) const int P8 = -1;
layout(constant_id = 10) const int P9 = -1;
layout(constant_id = 11) const int P10 = -1;
layout(constant_id = 12) const int P11 = -1;
layout(constant_id = 13) const int P12 = -1;
layout(constant_id = 14) const int P13 = -1;
layout(constant_id = 15) const int P14 = -1;
layout(constant_id = 16) const int P15 = -1;
// k is a constant once the loops unroll, so this folds to the plan's parent.
int parent_of(int k) {
  return k == 0 ? P0 : k == 1 ? P1 : k == 2 ? P2 : k == 3 ? P3 : k == 4 ? P4 : k == 5 ? P5 :
         k == 6 ? P6 : k == 7 ? P7 : k == 8 ? P8 : k == 9 ? P9 : k == 10 ? P10 :
         k == 11 ? P11 : k == 12 ? P12 : k == 13 ? P13 : k == 14 ? P14 : P15;
}
#endif

// exp(-x) for x >= 0, the same reduction and degree-12 Taylor polynomial as exp_neg()
// in simd_exp.h (GLSL has no double exp).
double exp_neg(double x) {
  x = min(x, 700.0LF);
  precise double y = -x;
  const double shifter = 6755399441055744.0LF;  // 1.5 * 2^52: rounds to an integer
  precise double t = y * 1.4426950408889634074LF + shifter;
  precise double n = t - shifter;
  precise double r = y - n * 6.93147180369123816490e-01LF;
  r = r - n * 1.90821492927058770002e-10LF;
  precise double p = 1.0LF / 479001600.0LF;
  p = p * r + 1.0LF / 39916800.0LF;
  p = p * r + 1.0LF / 3628800.0LF;
  p = p * r + 1.0LF / 362880.0LF;
  p = p * r + 1.0LF / 40320.0LF;
  p = p * r + 1.0LF / 5040.0LF;
  p = p * r + 1.0LF / 720.0LF;
  p = p * r + 1.0LF / 120.0LF;
  p = p * r + 1.0LF / 24.0LF;
  p = p * r + 1.0LF / 6.0LF;
  p = p * r + 0.5LF;
  p = p * r + 1.0LF;
  p = p * r + 1.0LF;
  // times 2^n by adding n to the exponent bits (no ldexp: it does not vectorise)
  uvec2 bits = unpackDouble2x32(p);
  bits.y += uint(int(n)) << 20;
  return packDouble2x32(bits);
}

void main() {
  // One subgroup per point: the lanes take consecutive candidates of each row (contiguous
  // loads, and every lane loops the same rows), then the sums are reduced across lanes.
  uint i = pc.base + gl_WorkGroupID.x * gl_NumSubgroups + gl_SubgroupID;
  if (i >= pc.n) return;
  dvec4 p = sorted_pos[i];
  const dvec3 lo = p.xyz, hi = p.xyz;
  const uint first = gl_SubgroupInvocationID, step = gl_SubgroupSize;
  double sw[NS];
  double sh[NS];
  for (int k = 0; k < NS; ++k) {
    sw[k] = 0.0LF;
    sh[k] = 0.0LF;
  }
  // The plan in registers (reading the buffer in the inner loop costs a load per use).
  // Every array here is indexed by constants only once loops unroll, so it stays in
  // registers (a dynamic index would move it to memory).
  double ct[NS];
  for (int k = 0; k < NS; ++k) ct[k] = cut2[k];
#ifdef FAST8
  const double cf0 = coef[0], cf1 = coef[1], cf2 = coef[2];
#else
  double cf[NS];
  for (int k = 0; k < NS; ++k) cf[k] = coef[k];
#endif
  uint count = 0u;
  const double c = pc.h;
  const double R2 = pc.radius2;
  // Cell ranges as sweep_point() derives them (same doubles, same floors) around the box
  // [lo, hi] (a single point, or the subgroup's points).
  const double R = sqrt(R2);
  int zlo = max(0, int(floor((lo.z - R) / c))), zhi = min(int(pc.nz) - 1, int(floor((hi.z + R) / c)));
  int ylo = max(0, int(floor((lo.y - R) / c))), yhi = min(int(pc.ny) - 1, int(floor((hi.y + R) / c)));
  for (int z = zlo; z <= zhi; ++z) {
    double dz = max(0.0LF, max(double(z) * c - hi.z, lo.z - double(z + 1) * c));
    for (int y = ylo; y <= yhi; ++y) {
      double dy = max(0.0LF, max(double(y) * c - hi.y, lo.y - double(y + 1) * c));
      double rest = R2 - dz * dz - dy * dy;
      if (rest <= 0.0LF) continue;
      double hx = sqrt(rest);
      int xa = max(0, int(floor((lo.x - hx) / c)));
      int xb = min(int(pc.nx) - 1, int(floor((hi.x + hx) / c)));
      uint row = pc.nx * (uint(y) + pc.ny * uint(z));
      uint j0 = starts[row + uint(xa)];
      uint j1 = starts[row + uint(xb) + 1u];
      for (uint j = j0 + first; j < j1; j += step) {
        dvec4 q = sorted_pos[j];
        precise dvec3 d = q.xyz - p.xyz;
        precise double d2 = d.x * d.x + d.y * d.y + d.z * d.z;
        count += (d2 < R2) ? 1u : 0u;
#ifdef FAST8
        double w[8];
        w[0] = exp_neg(d2 * cf0);  // 12 eps
        w[1] = exp_neg(d2 * cf1);  // 10 eps
        w[2] = exp_neg(d2 * cf2);  // 8 eps
        double t;
        t = w[0] * w[0]; w[3] = t * t;  // 6 eps
        t = w[1] * w[1]; w[4] = t * t;  // 5 eps
        t = w[2] * w[2]; w[5] = t * t;  // 4 eps
        t = w[3] * w[3]; w[6] = t * t;  // 3 eps
        t = w[5] * w[5]; w[7] = t * t;  // 2 eps
        for (int k = 0; k < 8; ++k) {
          double m = (d2 < ct[k]) ? w[k] : 0.0LF;
          sh[k] += m * q.w;
          sw[k] += m;
        }
#else
        double w[NS];
        for (int k = 0; k < NS; ++k) {
          if (parent_of(k) < 0) {
            w[k] = exp_neg(d2 * cf[k]);
          } else {
            double t = w[parent_of(k)] * w[parent_of(k)];
            w[k] = t * t;
          }
          double m = (d2 < ct[k]) ? w[k] : 0.0LF;
          sh[k] += m * q.w;
          sw[k] += m;
        }
#endif
      }
    }
  }
  for (int k = 0; k < NS; ++k) {  // no early exit: constant indices keep the sums in registers
    sw[k] = subgroupAdd(sw[k]);
    sh[k] = subgroupAdd(sh[k]);
  }
  count = subgroupAdd(count);
  if (!subgroupElect()) return;
  // The averages go to their own array: indexing the accumulators with out_a/out_b would
  // force them out of registers into memory for the whole loop.
  double g[NS];
  for (int k = 0; k < NS; ++k) g[k] = sh[k] / max(sw[k], 1.0LF);  // sw >= 1 (the point itself)
  uint v = sorted_vertex[i];
  for (int o = 0; o < int(pc.nout); ++o) {
    int a = out_a[o], b = out_b[o];
    result[uint(o) * pc.stride + v] = (b < 0) ? g[a] : abs(g[a] - g[b]);
  }
  pairs[i] = count;
}
