// CPU twin: sweep_point_default() / sweep_point_generic() in src/saliency/sweep_kernels.inc
// meshsal: the neighbour sweep, GPU twin of gaussian_filter() and its kernels
// (gaussian_filter.cpp, sweep_kernels.inc), in double like the CPU, or mixed (MIXED below:
// float distances and weights, float sums of a few terms folded into doubles, exact
// cutoffs, and an error bound per map with which gpu_sweep.cpp rechecks near ties of the
// local-maximum test in double). GPUs give each mesh point a subgroup, in cell order: like
// the CPU's 4-wide loop, the lanes split the candidates of a row between them; on CPU
// devices (lavapipe) sweep8_rows gives each point a lane (UNIFORM_ROWS below). Each
// layout's main() is in its own file (sweep_layout_subgroup/rows/list.glsl). Rows of
// cells are culled against the ball as on the CPU; the cells of a row are one contiguous
// range of the sorted points. Every candidate adds its weight to all sigma sums at once,
// masked by each sigma's strict cutoff d < 2 s (no branches: lavapipe runs 8 lanes of
// AVX2). Weights of a sigma half of another are w(s) = w(2s)^4, as in the CPU's
// KernelPlan. The center-surround step S_i = |G(s_i) - G(2 s_i)| is done here too, so only
// the raw maps are written. Included by sweep8.comp and sweep8_rows.comp (the default
// sigmas 12,10,8,6,5,4,3,2 eps, fixed plan: FAST8), their _mixed twins, sweep8_list.comp
// (the double recheck of listed vertices: POINT_LIST) and sweepn.comp (any plan of up to
// 16 sigmas, specialised per plan).
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
#ifdef MIXED
// The mixed-precision sweep (sweep8_mixed, sweep8_rows_mixed): the points again as the
// input's float coordinates (not shifted: then q - p rounds with a relative error of at
// most 2^-24 per component) and the value as a float; and per vertex the bound on the
// error of every raw map that near_tie.comp uses.
layout(std430, binding = 6) readonly buffer Sorted32 { vec4 sorted_pos32[]; };
layout(std430, binding = 7) writeonly buffer Bound { float error_bound[]; };
#endif
#ifdef POINT_LIST
// The double recheck of listed vertices (sweep8_list): positions by vertex, as pos[] holds
// them (the same doubles as sorted_pos), and the vertices to sweep.
layout(std430, binding = 6) readonly buffer VertexPos { dvec4 vertex_pos[]; };
layout(std430, binding = 7) readonly buffer List { uint point_list[]; };
#endif
layout(push_constant) uniform Push {
  uint base; uint n;          // sorted points [base, n) of this submission
  uint nx; uint ny; uint nz;  // grid size in cells
  uint per_group;             // points per work group the host counted on (subgroup per point)
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
#if defined(UNIFORM_ROWS) || defined(POINT_LIST)
#define ONE_LANE_PER_POINT
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
// gaussian_filter.cpp, the shared degree-7 polynomial (exp_poly7.glsl). A multiply and an
// add per step on every device: the CPU build no longer contracts them into an fma
// (-ffp-contract=off), and lavapipe runs a double fma() far slower than a * b + c.
#include "exp_poly7.glsl"
double exp_neg_small(double x) { return exp_neg_poly7(x); }
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

#ifdef MIXED
// The mixed sweep's accuracy, and the error bound it writes for every raw map (u = 2^-24,
// first order in u throughout):
// * d2 = |q - p|^2 from float coordinates: each q - p rounds once (relative u), then three
//   squares and two adds: d2 within 5u of the exact squared distance.
// * The strict cutoffs are decided exactly: with n = d2 / (4 eps^2) every cutoff is an
//   integer (144, 100, 64, 36, 25, 16, 9, 4), and a float comparison can differ from the
//   CPU's double one only when n is within ~13u n of one; every candidate within 32u n of
//   an integer has its d2 recomputed in double from sorted_pos and is put on the side of
//   the nearby cutoff that the double says (the other cutoffs are >= 20% away).
// * Weights: with t = d2 / (2 eps^2), a = exp(-t/576) and c = exp(-t/400) are degree-8
//   Taylor polynomials in float (y = t/576 or t/400 <= 1/2 where they count: truncation
//   below u/10, Horner rounding <= (1 + 2y)u <= 2u) and every weight is a power a^m or
//   c^m: 12 eps a^4, 10 eps c^4, 8 eps a^9, 6 eps a^16, 5 eps c^16, 4 eps a^36, 3 eps
//   a^64, 2 eps a^144. A power m errs by at most 2m u (the base), 12u (at most 12
//   roundings of the products) and 14u (the argument: t is within 7u relative and the
//   weight's exponent is below 2 where it counts).
// * The value H as a float (u), the product w H (u) and the float sums: a lane sums at
//   most CHUNK * PER_STEP = 16 terms (lane per point) or, a subgroup per point, at most
//   FOLDS = 8 float sums of CHUNK = 8 terms each, before adding into a double (at most
//   15u or 14u of the sum of |terms|; on GPUs with fp64 at 1/32..1/64 rate the double
//   adds would cost more than the float work if they came every 8 candidates): every
//   numerator N = sum w H and denominator D = sum w errs by at most rho = (2m + 48)u
//   relative to A = sum w |H| and to D.
// * G = N / D then errs by at most rho (A / D + |G|) <= 2 rho A / D, and
//   S = |G(s) - G(2s)| by the sum of that for both sigmas. The bound written per map is
//   1.25 times that (the A are summed alongside, in the same arithmetic).
// A comparison of two neighbours' raw values further apart than the sum of their bounds
// falls as in double; near_tie.comp sends the others to a double recheck.
#define CHUNK 8u
#ifndef UNIFORM_ROWS
#define FOLDS 8u  // a subgroup per point: two levels of float sums
#endif
const float kCutoffTol = 1.0 / 524288.0;  // 32u = 2^-19
const float kU = 1.0 / 16777216.0;        // 2^-24
// exp(-y) for 0 <= y (<= 1/2 where it counts). Clamped at 1/2, so that a^144 >= e^-72
// stays a normal float: an underflow to a denormal costs a microcode assist on x86.
float exp_neg_half(float y) {
  y = min(y, 0.5);
  float p = 1.0 / 40320.0;
  p = p * -y + 1.0 / 5040.0;
  p = p * -y + 1.0 / 720.0;
  p = p * -y + 1.0 / 120.0;
  p = p * -y + 1.0 / 24.0;
  p = p * -y + 1.0 / 6.0;
  p = p * -y + 0.5;
  p = p * -y + 1.0;
  return p * -y + 1.0;
}
#endif

// Sweeps point p (its sums over the rows of cells around the box [lo, hi], which holds p):
// lanes first, first + step, ... of the rows' candidates; writes output vertex v unless
// !live (a lane past the end that only helps its subgroup's loads) or !elect.
void sweep_point(uint i, dvec4 p, dvec3 lo, dvec3 hi, uint first, uint step, bool live, uint v) {
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
#ifdef MIXED
  float ctf[NS];
  for (int k = 0; k < NS; ++k) ctf[k] = float(ct[k]);
  const double eps2 = ct[NS - 1] / 16.0LF;  // eps^2: the 2 eps cutoff is 16 eps^2
  const float inv4e2 = float(0.25LF / eps2);
  const float ca = float(1.0LF / (2.0LF * eps2 * 576.0LF));  // a = exp(-d2 ca)
  const float cc = float(1.0LF / (2.0LF * eps2 * 400.0LF));  // c = exp(-d2 cc)
  const vec3 p32 = sorted_pos32[i].xyz;
  double sa[NS];  // A = sum w |H|, for the error bound
  for (int k = 0; k < NS; ++k) sa[k] = 0.0LF;
#elif defined(FAST8)
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
#ifdef MIXED
      // Float sums over chunks of at most CHUNK steps; FOLDS of them summed in float, then
      // added into the doubles.
      for (uint j = j0 + first; j < j1;) {
#ifdef FOLDS
        const uint jfold = min(j1, j + FOLDS * CHUNK * PER_STEP * step);
        float gw[NS], gh[NS], ga[NS];
        for (int k = 0; k < NS; ++k) {
          gw[k] = 0.0;
          gh[k] = 0.0;
          ga[k] = 0.0;
        }
        while (j < jfold) {
        const uint jend = min(jfold, j + CHUNK * PER_STEP * step);
#else
        const uint jend = min(j1, j + CHUNK * PER_STEP * step);
#endif
        float fw[NS], fh[NS], fa[NS];
        for (int k = 0; k < NS; ++k) {
          fw[k] = 0.0;
          fh[k] = 0.0;
          fa[k] = 0.0;
        }
        for (; j < jend; j += PER_STEP * step) {
          float w[PER_STEP][NS];
          float dist2[PER_STEP], value[PER_STEP];
          for (uint u = 0u; u < PER_STEP; ++u) {
            const uint ju = j + u * step;
            const bool inside = u == 0u || ju < j1;
            const uint jq = inside ? ju : j;
            vec4 q = sorted_pos32[jq];
            vec3 d = q.xyz - p32;
            float d2 = d.x * d.x + d.y * d.y + d.z * d.z;
            const float n = d2 * inv4e2;
            const float nr = roundEven(n);
            if (abs(n - nr) <= kCutoffTol * n) {
              // Near a cutoff: which side of it, in double as on the CPU (rare).
              dvec3 e = sorted_pos[jq].xyz - p.xyz;
              double d2d = e.x * e.x + e.y * e.y + e.z * e.z;
              for (int k = 0; k < NS; ++k)
                if (abs(ctf[k] * inv4e2 - nr) < 0.5)
                  d2 = d2d < ct[k] ? min(d2, ctf[k] * (1.0 - 1.0 / 8388608.0)) : max(d2, ctf[k]);
            }
            d2 = inside ? d2 : ctf[0];
            count += (d2 < ctf[0]) ? 1u : 0u;
            // Powers of a = exp(-t/576) and c = exp(-t/400) (see above).
            const float a = exp_neg_half(d2 * ca), c = exp_neg_half(d2 * cc);
            const float a2 = a * a, a4 = a2 * a2, a8 = a4 * a4, a16 = a8 * a8, a32 = a16 * a16,
                        a64 = a32 * a32, a128 = a64 * a64, c2 = c * c, c4 = c2 * c2, c8 = c4 * c4;
            w[u][0] = a4;           // 12 eps
            w[u][1] = c4;           // 10 eps
            w[u][2] = a8 * a;       //  8 eps
            w[u][3] = a16;          //  6 eps
            w[u][4] = c8 * c8;      //  5 eps
            w[u][5] = a32 * a4;     //  4 eps
            w[u][6] = a64;          //  3 eps
            w[u][7] = a128 * a16;   //  2 eps
            dist2[u] = d2;
            value[u] = q.w;
          }
          for (int k = 0; k < NS; ++k) {
            float m = (dist2[0] < ctf[k]) ? w[0][k] : 0.0;
            float h = m * value[0], s = m, ab = m * abs(value[0]);
            for (uint u = 1u; u < PER_STEP; ++u) {
              m = (dist2[u] < ctf[k]) ? w[u][k] : 0.0;
              h += m * value[u];
              s += m;
              ab += m * abs(value[u]);
            }
            fh[k] += h;
            fw[k] += s;
            fa[k] += ab;
          }
        }
#ifdef FOLDS
        for (int k = 0; k < NS; ++k) {
          gh[k] += fh[k];
          gw[k] += fw[k];
          ga[k] += fa[k];
        }
        }
        for (int k = 0; k < NS; ++k) {
          sh[k] += double(gh[k]);
          sw[k] += double(gw[k]);
          sa[k] += double(ga[k]);
        }
#else
        for (int k = 0; k < NS; ++k) {
          sh[k] += double(fh[k]);
          sw[k] += double(fw[k]);
          sa[k] += double(fa[k]);
        }
#endif
      }
#else
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
#endif
    }
  }
#ifdef ONE_LANE_PER_POINT
  if (!live) return;
#else
  for (int k = 0; k < NS; ++k) {  // no early exit: constant indices keep the sums in registers
    sw[k] = subgroupAdd(sw[k]);
    sh[k] = subgroupAdd(sh[k]);
  }
  count = subgroupAdd(count);
#ifdef MIXED
  for (int k = 0; k < NS; ++k) sa[k] = subgroupAdd(sa[k]);
#endif
  if (!subgroupElect()) return;
#endif
  // The averages go to their own array: indexing the accumulators with out_a/out_b would
  // force them out of registers into memory for the whole loop.
  double g[NS];
  for (int k = 0; k < NS; ++k) g[k] = sh[k] / max(sw[k], 1.0LF);  // sw >= 1 (the point itself)
  for (int o = 0; o < int(pc.nout); ++o) {
    int a = out_a[o], b = out_b[o];
    result[uint(o) * pc.stride + v] = (b < 0) ? g[a] : abs(g[a] - g[b]);
  }
#ifdef MIXED
  // Per map: 1.25 (2 rho_a A_a / D_a + 2 rho_b A_b / D_b), rho = (2m + 48)u (see above).
  const float power[NS] = float[NS](4.0, 4.0, 9.0, 16.0, 16.0, 36.0, 64.0, 144.0);
  double e[NS];
  for (int k = 0; k < NS; ++k) e[k] = 2.5LF * double((2.0 * power[k] + 48.0) * kU) * sa[k] / max(sw[k], 1.0LF);
  for (int o = 0; o < int(pc.nout); ++o) {
    int a = out_a[o], b = out_b[o];
    error_bound[uint(o) * pc.stride + v] = float(e[a] + ((b < 0) ? 0.0LF : e[b]));
  }
#endif
#ifndef POINT_LIST
  pairs[i] = count;  // >= 1 (the point itself): the host checks that no point was left out
#endif
}
