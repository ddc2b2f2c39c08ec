// libFuzzer target "gltf" (see fuzz_load.h and tools/fuzz.sh).
#include "fuzz_load.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  meshsal_fuzz::run_target("gltf", data, size);
  return 0;
}
