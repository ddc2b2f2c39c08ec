// meshsal: exp(-x) by its degree-7 Taylor polynomial, the one copy on the CPU side. The
// GPU side's copy is shaders/exp_poly7.glsl; tests/core/test_exp_poly7.cpp reads that
// file and holds its coefficients equal to these, bit for bit.
//   - The exact sweep's default plan (gaussian_filter.cpp, sweep.glsl) uses it as is on
//     0 <= x <= 0.02: truncation error < x^8/8! < 1e-18 relative, so it is exp(-x) to
//     rounding (measured: 1.1e-16 relative at most).
//   - The fast method (gaussian_filter_fast.cpp, fast_query.comp) uses exp_neg_cutoff(x) =
//     exp_neg_poly7(x/4)^4 on 0 <= x < 2 (inside the 2-sigma cutoff): largest relative error
//     6.05e-7 (6.0512e-7 as x -> 2; tests/core/test_exp_poly7.cpp measures it over the range),
//     far below the error of the method's cells. The CPU queries evaluate it in float
//     (float or v8f: 1.12e-6 at most, measured there).
// Estrin's scheme (below), a multiply then an add per step (never an fma: the build has
// -ffp-contract=off, and the GPU code marks the same steps `precise`).
#pragma once
#include "core/simd_exp.h"

namespace meshsal {
inline namespace MESHSAL_SIMD_ISA {  // see simd_exp.h

// kExpPoly7[k] = (-1)^k / k!, the coefficient of x^k.
constexpr double kExpPoly7[8] = {1.0,         -1.0,         0.5,          -1.0 / 6.0,
                                 1.0 / 24.0,  -1.0 / 120.0, 1.0 / 720.0,  -1.0 / 5040.0};

template <class T>
inline T exp_poly7_splat(double c);
template <>
inline double exp_poly7_splat<double>(double c) { return c; }
template <>
inline v4d exp_poly7_splat<v4d>(double c) { return v4d_splat(c); }
// In float (the fast method's queries): the coefficients rounded to float.
template <>
inline float exp_poly7_splat<float>(double c) { return float(c); }
template <>
inline v8f exp_poly7_splat<v8f>(double c) { return v8f_splat(float(c)); }

// sum_k kExpPoly7[k] x^k, for double or v4d, float or v8f (lane by lane, the same
// operations), by Estrin's scheme: pairs c_k + c_k+1 x, combined with x^2 and x^4. Its longest chain is 5
// dependent operations, Horner's 14: without fma contraction, Horner left the exact sweep
// of the default scales (latency-bound) ~40% slower than the -march=x86-64-v3 build with
// contraction had been.
template <class T>
inline T exp_neg_poly7(T x) {
  const T x2 = x * x, x4 = x2 * x2;
  const T p01 = exp_poly7_splat<T>(kExpPoly7[1]) * x + exp_poly7_splat<T>(kExpPoly7[0]);
  const T p23 = exp_poly7_splat<T>(kExpPoly7[3]) * x + exp_poly7_splat<T>(kExpPoly7[2]);
  const T p45 = exp_poly7_splat<T>(kExpPoly7[5]) * x + exp_poly7_splat<T>(kExpPoly7[4]);
  const T p67 = exp_poly7_splat<T>(kExpPoly7[7]) * x + exp_poly7_splat<T>(kExpPoly7[6]);
  const T q03 = p23 * x2 + p01, q47 = p67 * x2 + p45;
  return q47 * x4 + q03;
}

// exp(-x) for 0 <= x < 2: exp_neg_poly7(x/4)^4.
template <class T>
inline T exp_neg_cutoff(T x) {
  T p = exp_neg_poly7(x * exp_poly7_splat<T>(0.25));
  p = p * p;
  return p * p;
}

}  // namespace MESHSAL_SIMD_ISA
}  // namespace meshsal
