// libFuzzer target "rows": ground-truth text rows of meshsal eval, parsed and joined to a
// mesh (see fuzz_load.h and tools/fuzz.sh).
#include "fuzz_load.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  meshsal_fuzz::run_target("rows", data, size);
  return 0;
}
