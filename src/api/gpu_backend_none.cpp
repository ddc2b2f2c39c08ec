// meshsal: the library's backend switch (api/gpu_backend.h) in meshsal::core, the library
// without Vulkan: there is no GPU backend, and gpu_backend() refuses every GPU request.
#include "api/gpu_backend.h"

namespace meshsal {

const GpuBackend* linked_gpu_backend() { return nullptr; }

}  // namespace meshsal
