#include "saliency/cpu_dispatch.h"

#include <atomic>
#include <cstdlib>
#include <cstring>

#include "meshsal/meshsal.h"

namespace meshsal {

namespace {

// -1: no test override; else the CpuPath forced by ScopedCpuPathForTests.
std::atomic<int> forced_path{-1};

bool cpu_has_avx2() {
#if MESHSAL_HAVE_AVX2_COPIES
  __builtin_cpu_init();
  return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
#else
  return false;
#endif
}

bool baseline_requested() {
  const char* v = std::getenv("MESHSAL_CPU_BASELINE");
  return v && *v && std::strcmp(v, "0") != 0;
}

CpuPath default_path() {
  static const CpuPath path =
      cpu_has_avx2() && !baseline_requested() ? CpuPath::avx2 : CpuPath::baseline;
  return path;
}

}  // namespace

bool cpu_avx2_available() {
  static const bool available = cpu_has_avx2();
  return available;
}

CpuPath cpu_path() {
  const int forced = forced_path.load(std::memory_order_relaxed);
  return forced >= 0 ? CpuPath(forced) : default_path();
}

const char* cpu_path_name(CpuPath path) { return path == CpuPath::avx2 ? "avx2" : "baseline"; }

ScopedCpuPathForTests::ScopedCpuPathForTests(CpuPath path) : previous_(forced_path.load()) {
  if (path == CpuPath::avx2 && !cpu_avx2_available())
    throw Error("the AVX2 path is not available (no AVX2+FMA on this CPU, or not built)");
  forced_path.store(int(path));
}

ScopedCpuPathForTests::~ScopedCpuPathForTests() { forced_path.store(previous_); }

}  // namespace meshsal
