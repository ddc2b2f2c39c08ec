// meshsal: run-time choice of the CPU hot loops (issue 26, README "Portable build").
// The library is built for baseline x86-64, and the hot loops a second time for AVX2+FMA:
//   - the exact sweep and the fast method's queries (saliency/sweep_kernels.h): one body,
//     sweep_kernels.inc, compiled by two files, one of them with -mavx2 -mfma;
//   - the curvature (curvature.cpp, scalar code): a baseline and an AVX2 copy of each loop
//     in the same file (MESHSAL_TARGET_AVX2: the target attribute plus `flatten`, so that
//     what the loop calls is inlined into the copy and compiled for AVX2).
// Both copies run the same IEEE operations in the same order (-ffp-contract=off: no a*b+c
// becomes an fma, and no fma intrinsic is used), so their results are bit-identical; AVX2
// does them 4 lanes at a time instead of 2.
#pragma once

namespace meshsal {

enum class CpuPath { baseline, avx2 };

// The path the hot loops take now: avx2 where this build has the AVX2 copies, the CPU has
// AVX2 and FMA and the environment variable MESHSAL_CPU_BASELINE is unset, empty or "0"
// (read once, at the first call); else baseline.
CpuPath cpu_path();

// Whether the AVX2 copies exist in this build and the CPU can run them.
bool cpu_avx2_available();

const char* cpu_path_name(CpuPath path);

// Tests only (an internal header, not the public API): the hot loops take `path` while
// the object lives (avx2 where cpu_avx2_available(), else throws meshsal::Error). Not for
// use while another thread runs a filter.
class ScopedCpuPathForTests {
 public:
  explicit ScopedCpuPathForTests(CpuPath path);
  ~ScopedCpuPathForTests();
  ScopedCpuPathForTests(const ScopedCpuPathForTests&) = delete;
  ScopedCpuPathForTests& operator=(const ScopedCpuPathForTests&) = delete;

 private:
  int previous_;
};

}  // namespace meshsal

// The AVX2 copy of a hot loop: `MESHSAL_TARGET_AVX2 void f_avx2(...) { f_body(...); }`.
// CMakeLists.txt defines MESHSAL_AVX2_KERNELS for the files that make or choose the AVX2
// copies (sweep_kernels_*.cpp, curvature.cpp, cpu_dispatch.cpp) where the target is x86-64
// and the compiler takes -mavx2 -mfma; elsewhere there is only the baseline.
#if defined(MESHSAL_AVX2_KERNELS)
#define MESHSAL_HAVE_AVX2_COPIES 1
#define MESHSAL_TARGET_AVX2 __attribute__((target("avx2,fma"), flatten))
#else
#define MESHSAL_HAVE_AVX2_COPIES 0
#endif
// The baseline copy, flattened alike so that both copies are the same code but for the ISA.
#define MESHSAL_TARGET_BASELINE __attribute__((flatten))
