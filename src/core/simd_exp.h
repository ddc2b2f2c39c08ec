// meshsal: exp(-x) on 4 doubles at once (GCC vector extensions), accurate to ~1 ulp.
// The Gaussian sweep evaluates millions of weights per second; std::exp does not vectorise.
#pragma once
#include <cstdint>
#include <cstring>

// The CPU hot loops are compiled for two instruction sets (saliency/sweep_kernels.h), and
// these inline helpers with them: an inline namespace per instruction set gives each its
// own symbols, so that an out-of-line copy compiled for AVX2 is never the one the linker
// keeps for a baseline caller.
#if defined(__AVX2__)
#define MESHSAL_SIMD_ISA isa_avx2
#else
#define MESHSAL_SIMD_ISA isa_baseline
#endif

namespace meshsal {
inline namespace MESHSAL_SIMD_ISA {

typedef double v4d __attribute__((vector_size(32)));
typedef int64_t v4i __attribute__((vector_size(32)));

inline v4d v4d_splat(double x) { return v4d{x, x, x, x}; }

inline v4d v4d_load(const double* p) {
  v4d v;
  std::memcpy(&v, p, sizeof v);
  return v;
}

// 8 floats (the fast method's queries, sweep_kernels.inc): one AVX register, or two SSE
// ones on baseline x86-64, lane by lane the same IEEE operations either way.
typedef float v8f __attribute__((vector_size(32)));
typedef int32_t v8i __attribute__((vector_size(32)));

inline v8f v8f_splat(float x) { return v8f{x, x, x, x, x, x, x, x}; }

inline v8f v8f_load(const float* p) {
  v8f v;
  std::memcpy(&v, p, sizeof v);
  return v;
}

// exp(-x) for x >= 0 (x is clamped to 700, where exp(-x) ~ 1e-304 is as good as 0).
// Cody-Waite reduction x*log2(e) = n + r/ln2, |r| <= ln2/2, then a degree-12 Taylor
// polynomial (truncation < 2e-16) and 2^n put into the exponent bits directly.
inline v4d exp_neg(v4d x) {
  const v4d limit = v4d_splat(700.0);
  x = x < limit ? x : limit;  // lane-wise select (GCC vector extension)
  v4d y = -x;
  const v4d shifter = v4d_splat(6755399441055744.0);  // 1.5 * 2^52: rounds to integer
  v4d t = y * v4d_splat(1.4426950408889634074) + shifter;
  v4d n = t - shifter;
  v4d r = y - n * v4d_splat(6.93147180369123816490e-01);
  r = r - n * v4d_splat(1.90821492927058770002e-10);
  v4d p = v4d_splat(1.0 / 479001600.0);
  p = p * r + v4d_splat(1.0 / 39916800.0);
  p = p * r + v4d_splat(1.0 / 3628800.0);
  p = p * r + v4d_splat(1.0 / 362880.0);
  p = p * r + v4d_splat(1.0 / 40320.0);
  p = p * r + v4d_splat(1.0 / 5040.0);
  p = p * r + v4d_splat(1.0 / 720.0);
  p = p * r + v4d_splat(1.0 / 120.0);
  p = p * r + v4d_splat(1.0 / 24.0);
  p = p * r + v4d_splat(1.0 / 6.0);
  p = p * r + v4d_splat(0.5);
  p = p * r + v4d_splat(1.0);
  p = p * r + v4d_splat(1.0);
  // The low bits of t hold n (two's complement offset by the shifter's bits).
  v4i tb, sb, pb;
  std::memcpy(&tb, &t, sizeof t);
  std::memcpy(&sb, &shifter, sizeof t);
  std::memcpy(&pb, &p, sizeof p);
  pb += (tb - sb) << 52;
  std::memcpy(&p, &pb, sizeof p);
  return p;
}

}  // namespace MESHSAL_SIMD_ISA
}  // namespace meshsal
