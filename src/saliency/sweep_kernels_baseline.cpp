// meshsal: the CPU hot loops (sweep_kernels.h) for baseline x86-64, and the choice between
// them and the AVX2 ones.
#define MESHSAL_KERNELS_NAME kBaselineKernels
#include "saliency/sweep_kernels.inc"

#include "saliency/cpu_dispatch.h"

namespace meshsal::sweep {

const Kernels& kernels() {
#ifdef MESHSAL_AVX2_KERNELS
  if (cpu_path() == CpuPath::avx2) return kAvx2Kernels;
#endif
  return kBaselineKernels;
}

}  // namespace meshsal::sweep
