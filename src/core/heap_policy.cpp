#include "core/heap_policy.h"

#include <climits>
#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace meshsal {

void keep_freed_memory_for_reuse() {
#if defined(__GLIBC__)
  mallopt(M_MMAP_MAX, 0);              // large blocks from the heap, not from their own mappings
  mallopt(M_TRIM_THRESHOLD, INT_MAX);  // and the heap's free top kept, not given back
#endif
}

}  // namespace meshsal
