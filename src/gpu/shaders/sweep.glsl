// meshsal: the neighbour sweep, GPU twin of gaussian_filter() / sweep_point()
// (gaussian_filter.cpp), in double like the CPU so that near-ties in the local-maximum
// test fall the same way. GPUs give each mesh point a subgroup, in cell order: like the
// CPU's 4-wide loop, the lanes split the candidates of a row between them; on CPU devices
// (lavapipe) sweep8_rows gives each point a lane (UNIFORM_ROWS below). Rows of cells are
// culled against the ball as on the CPU; the cells of a row are one contiguous range of the sorted points. Every
// candidate adds its weight to all sigma sums at once, masked by each sigma's strict
// cutoff d < 2 s (no branches: lavapipe runs 8 lanes of AVX2). Weights of a sigma half of
// another are w(s) = w(2s)^4, as in the CPU's KernelPlan. The center-surround step
// S_i = |G(s_i) - G(2 s_i)| is done here too, so only the raw maps are written.
// Included by sweep8.comp and sweep8_rows.comp (the default sigmas 12,10,8,6,5,4,3,2 eps,
// fixed plan: FAST8) and sweepn.comp (any plan of up to 16 sigmas, specialised per plan).
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
  double bcoef;  // sweep8 only: b = exp(-d2 * bcoef), see sweep_point_default()
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

// Candidates per lane and loop iteration. Two on CPU devices: lavapipe keeps the 16 sums
// in memory and stores them under the lane mask once per iteration, so this halves that
// traffic (dragon_50k's sweep, best of 5: 0.66 s -> 0.49 s; four per step was slower).
#ifdef UNIFORM_ROWS
#define PER_STEP 2u
#else
#define PER_STEP 1u
#endif

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

#ifdef FAST8
// exp(-x) for 0 <= x <= 0.02 (Taylor, truncation < 1e-18): exp_neg_small() in
// gaussian_filter.cpp.
double exp_neg_small(double x) {
  // The CPU build contracts p * x + c to an fma (x86-64-v3, GCC's -ffp-contract=fast); so
  // does the GPU variant. Not sweep8_rows: lavapipe runs a double fma() far slower than
  // a * b + c (its igea_134k sweep went from 2.0 s to 2.8 s).
#ifdef UNIFORM_ROWS
#define MAD(a, b, c) ((a) * (b) + (c))
#else
#define MAD(a, b, c) fma(a, b, c)
#endif
  double p = -1.0LF / 5040.0LF;
  p = MAD(p, x, 1.0LF / 720.0LF);
  p = MAD(p, x, -1.0LF / 120.0LF);
  p = MAD(p, x, 1.0LF / 24.0LF);
  p = MAD(p, x, -1.0LF / 6.0LF);
  p = MAD(p, x, 0.5LF);
  p = MAD(p, x, -1.0LF);
  return MAD(p, x, 1.0LF);
#undef MAD
}
#endif

// The weights of a candidate at squared distance d2 for every sigma, before the cutoffs
// (in FAST8, 0 for all at or past the largest cutoff, cut0).
#ifdef FAST8
void candidate_weights(double d2, double cut0, double cb, out double w[NS]) {
#else
void candidate_weights(double d2, const double cf[NS], out double w[NS]) {
#endif
#ifdef FAST8
  // The CPU twin is sweep_point_default() (gaussian_filter.cpp), line for line:
  // with t = d2 / (2 eps^2) every weight is a power of b = exp(-t / 14400), and
  // t <= 288 inside the sweep radius, so b is a degree-7 Taylor polynomial; the
  // candidates at or past the radius get b = 0 (no branch, no overflow).
  //   CPU: v4d b = (d2 < cut[0]) ? exp_neg_small(d2 * cb) : zero;
  double b = (d2 < cut0) ? exp_neg_small(d2 * cb) : 0.0LF;
  //   CPU: b2 .. b128 by squaring; w12 = b64*b32*b4, w10 = b128*b16, w8 = b128*b64*b32*b
  double b2 = b * b, b4 = b2 * b2, b8 = b4 * b4, b16 = b8 * b8, b32 = b16 * b16,
         b64 = b32 * b32, b128 = b64 * b64;
  w[0] = b64 * b32 * b4;         // 12 eps: b^100
  w[1] = b128 * b16;             // 10 eps: b^144
  w[2] = b128 * b64 * b32 * b;   //  8 eps: b^225
  //   CPU: w(k) = w(2k)^4 for 6, 5, 4, 3, 2 eps
  double t;
  t = w[0] * w[0]; w[3] = t * t;  // 6 eps
  t = w[1] * w[1]; w[4] = t * t;  // 5 eps
  t = w[2] * w[2]; w[5] = t * t;  // 4 eps
  t = w[3] * w[3]; w[6] = t * t;  // 3 eps
  t = w[5] * w[5]; w[7] = t * t;  // 2 eps
#else
  for (int k = 0; k < NS; ++k) {
    if (parent_of(k) < 0) {
      w[k] = exp_neg(d2 * cf[k]);
    } else {
      double t = w[parent_of(k)] * w[parent_of(k)];
      w[k] = t * t;
    }
  }
#endif
}

void main() {
#ifdef UNIFORM_ROWS
  // One lane per point (lavapipe, where a lane is an AVX2 slot). The lanes of a subgroup
  // take consecutive sorted points and walk the rows of cells around the box of those of
  // the group's points that lie in their own row of cells, so they load the same
  // candidates at once and their loop bounds agree (except where a group straddles two
  // rows). Any box that holds the lane's own point gives the right sums; the group only
  // decides how much is shared. The box must stay small: with the box of all the
  // subgroup's points (by subgroupMin/Max or by these loads alike), a group straddling
  // rows walked a box across the whole mesh, and lavapipe gave fewer pairs than the CPU
  // and wrong sums for ~100 of igea_loop1's 537k points. Why lavapipe loses them there
  // was not found; with boxes of one row of cells igea_loop1 matches the CPU exactly.
  const uint gid = gl_GlobalInvocationID.x;
  const uint i = min(pc.base + gid, pc.n - 1u);
  const bool live = pc.base + gid < pc.n;
  const uint g0 = pc.base + gid - gid % gl_SubgroupSize;
  dvec4 p = sorted_pos[i];
  dvec3 lo = p.xyz, hi = p.xyz;
  const ivec2 my_row = ivec2(p.yz / pc.h);
  for (uint e = 0u; e < gl_SubgroupSize; ++e) {
    dvec3 o = sorted_pos[min(g0 + e, pc.n - 1u)].xyz;
    if (ivec2(o.yz / pc.h) == my_row) {
      lo = min(lo, o);
      hi = max(hi, o);
    }
  }
  // A row whose points lie far apart (two crossings of the surface): each lane alone.
  if (hi.x - lo.x > 2.0LF * pc.h) {
    lo = p.xyz;
    hi = p.xyz;
  }
  const uint first = 0u, step = 1u;
#else
  // One subgroup per point: the lanes take consecutive candidates of each row (contiguous
  // loads, and every lane loops the same rows), then the sums are reduced across lanes.
  uint i = pc.base + gl_WorkGroupID.x * gl_NumSubgroups + gl_SubgroupID;
  if (i >= pc.n) return;
  dvec4 p = sorted_pos[i];
  const dvec3 lo = p.xyz, hi = p.xyz;
  const uint first = gl_SubgroupInvocationID, step = gl_SubgroupSize;
#endif
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
  const double cb = bcoef;  // 1 / (2 eps^2 14400), computed as the CPU computes it
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
      // Each lane takes PER_STEP candidates per iteration, `step` apart; one past the row's
      // end is replaced by candidate j at distance^2 R2, where every (strict) cutoff masks it.
      for (uint j = j0 + first; j < j1; j += PER_STEP * step) {
        double w[PER_STEP][NS];
        double dist2[PER_STEP], value[PER_STEP];
        for (uint u = 0u; u < PER_STEP; ++u) {
          const uint ju = j + u * step;
          const bool inside = u == 0u || ju < j1;  // u == 0: j < j1 by the loop condition
          dvec4 q = sorted_pos[inside ? ju : j];
          precise dvec3 d = q.xyz - p.xyz;
          precise double d2 = d.x * d.x + d.y * d.y + d.z * d.z;
          d2 = inside ? d2 : R2;
          count += (d2 < R2) ? 1u : 0u;
#ifdef FAST8
          candidate_weights(d2, ct[0], cb, w[u]);
#else
          candidate_weights(d2, cf, w[u]);
#endif
          dist2[u] = d2;
          value[u] = q.w;
        }
        // Each sigma's cutoff masks the weights; the step's candidates are summed first,
        // then added once to each running sum.
        for (int k = 0; k < NS; ++k) {
          double m = (dist2[0] < ct[k]) ? w[0][k] : 0.0LF;
          double h = m * value[0], s = m;
          for (uint u = 1u; u < PER_STEP; ++u) {
            m = (dist2[u] < ct[k]) ? w[u][k] : 0.0LF;
            h += m * value[u];
            s += m;
          }
          sh[k] += h;
          sw[k] += s;
        }
      }
    }
  }
#ifdef UNIFORM_ROWS
  if (!live) return;
#else
  for (int k = 0; k < NS; ++k) {  // no early exit: constant indices keep the sums in registers
    sw[k] = subgroupAdd(sw[k]);
    sh[k] = subgroupAdd(sh[k]);
  }
  count = subgroupAdd(count);
  if (!subgroupElect()) return;
#endif
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
