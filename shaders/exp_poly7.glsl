// CPU twin: src/core/exp_poly7.h (the same coefficients; tests/test_exp_poly7.cpp)
// meshsal: exp(-x) by its degree-7 Taylor polynomial, the GPU side's one copy of
// src/core/exp_poly7.h (see there for where each use is exact enough). The coefficients
// are those of kExpPoly7[] there, written the same way (tests/test_exp_poly7.cpp reads this
// file and checks that they are equal bit for bit, so keep one `#define EXP_POLY7_Ck (...)`
// a line). Every step is a multiply then an add, `precise` so that no compiler fuses them
// into an fma: the CPU build has -ffp-contract=off, and the two sides agree to the bit.
// Needs GL_GOOGLE_include_directive in the including shader.
#ifndef MESHSAL_EXP_POLY7_GLSL
#define MESHSAL_EXP_POLY7_GLSL

#define EXP_POLY7_C0 (1.0LF)
#define EXP_POLY7_C1 (-1.0LF)
#define EXP_POLY7_C2 (0.5LF)
#define EXP_POLY7_C3 (-1.0LF / 6.0LF)
#define EXP_POLY7_C4 (1.0LF / 24.0LF)
#define EXP_POLY7_C5 (-1.0LF / 120.0LF)
#define EXP_POLY7_C6 (1.0LF / 720.0LF)
#define EXP_POLY7_C7 (-1.0LF / 5040.0LF)

// sum_k EXP_POLY7_Ck x^k: exp(-x) for small x >= 0; exp_neg_poly7() in exp_poly7.h, the
// same operations in the same order (Estrin's scheme).
double exp_neg_poly7(double x) {
  precise double x2 = x * x;
  precise double x4 = x2 * x2;
  precise double p01 = EXP_POLY7_C1 * x + EXP_POLY7_C0;
  precise double p23 = EXP_POLY7_C3 * x + EXP_POLY7_C2;
  precise double p45 = EXP_POLY7_C5 * x + EXP_POLY7_C4;
  precise double p67 = EXP_POLY7_C7 * x + EXP_POLY7_C6;
  precise double q03 = p23 * x2 + p01;
  precise double q47 = p67 * x2 + p45;
  precise double p = q47 * x4 + q03;
  return p;
}

// exp(-x) for 0 <= x < 2 (a weight inside the 2-sigma cutoff): exp_neg_poly7(x/4)^4,
// exp_neg_cutoff() in exp_poly7.h (largest relative error 6.05e-7).
double exp_neg_cutoff(double x) {
  precise double y = x * 0.25LF;
  precise double p = exp_neg_poly7(y);
  p = p * p;
  return p * p;
}

// The same two in float, the coefficients rounded to float: exp_neg_poly7<float> and
// exp_neg_cutoff<float> in exp_poly7.h (the fast method's queries; 1.12e-6 at most).
float exp_neg_poly7_f(float x) {
  precise float x2 = x * x;
  precise float x4 = x2 * x2;
  precise float p01 = float(EXP_POLY7_C1) * x + float(EXP_POLY7_C0);
  precise float p23 = float(EXP_POLY7_C3) * x + float(EXP_POLY7_C2);
  precise float p45 = float(EXP_POLY7_C5) * x + float(EXP_POLY7_C4);
  precise float p67 = float(EXP_POLY7_C7) * x + float(EXP_POLY7_C6);
  precise float q03 = p23 * x2 + p01;
  precise float q47 = p67 * x2 + p45;
  precise float p = q47 * x4 + q03;
  return p;
}

float exp_neg_cutoff_f(float x) {
  precise float y = x * 0.25;
  precise float p = exp_neg_poly7_f(y);
  p = p * p;
  return p * p;
}

#endif  // MESHSAL_EXP_POLY7_GLSL
