// meshsal: the CPU hot loops (sweep_kernels.h) for AVX2: CMakeLists.txt compiles this file
// with -mavx2 -mfma and MESHSAL_AVX2_KERNELS defined where the target is x86-64.
// -mfma changes nothing in the results: with -ffp-contract=off no a*b+c becomes an fma.
#ifdef MESHSAL_AVX2_KERNELS
#if !defined(__AVX2__) || !defined(__FMA__)
#error "sweep_kernels_avx2.cpp must be compiled with -mavx2 -mfma (see CMakeLists.txt)"
#endif
#define MESHSAL_KERNELS_NAME kAvx2Kernels
#include "saliency/sweep_kernels.inc"
#endif
