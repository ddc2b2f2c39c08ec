// meshsal: keep_freed_memory_for_reuse (meshsal.h), the heap policy a program may choose.
#include "meshsal/meshsal.h"

#include <climits>
#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace meshsal {

bool keep_freed_memory_for_reuse(bool on) {
#if defined(__GLIBC__)
  mallopt(M_MMAP_MAX, on ? 0 : 65536);                  // large blocks from the heap, not their own mappings
  mallopt(M_TRIM_THRESHOLD, on ? INT_MAX : 128 * 1024);  // and the heap's free top kept, not given back
  return true;
#else
  (void)on;
  return false;
#endif
}

}  // namespace meshsal
