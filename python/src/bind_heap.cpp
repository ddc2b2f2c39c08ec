// meshsal Python module: keep_freed_memory(). The library allocates its work buffers afresh
// in every call; where the C heap hands freed memory back to the system (glibc's default
// for large blocks), each call page-faults all of it in again: on bunny_36k that cost the
// Python call ~20% over the same call from the C++ tools, which keep their heap (as the
// meshsal command does, core/heap_policy.cpp). The module keeps it too unless asked not to.
#include <climits>
#if defined(__GLIBC__)
#include <malloc.h>
#endif

#include "bindings.h"

namespace meshsal_py {

namespace {

bool keep_freed_memory(bool on) {
#if defined(__GLIBC__)
  // Off: glibc's documented defaults (M_MMAP_MAX 65536, M_TRIM_THRESHOLD 128 KiB).
  mallopt(M_MMAP_MAX, on ? 0 : 65536);
  mallopt(M_TRIM_THRESHOLD, on ? INT_MAX : 128 * 1024);
  return true;
#else
  (void)on;
  return false;
#endif
}

}  // namespace

void bind_heap(py::module_& m) {
  m.def("keep_freed_memory", &keep_freed_memory, py::arg("on") = true,
        R"(keep_freed_memory(on=True) -> bool

Whether this process's C heap keeps memory it frees for reuse (on) or hands large blocks back
to the system (off: glibc's defaults). `import meshsal` turns it on, as the meshsal command
does: each call then reuses the memory of the previous one instead of page-faulting it in
again (about 20% of a saliency call on a 36k-vertex mesh). The price is that the process's
resident memory stays at its peak. Process-wide; returns False where the C library is not
glibc (nothing changed).)");
}

}  // namespace meshsal_py
