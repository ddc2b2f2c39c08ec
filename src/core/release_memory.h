// meshsal: free memory handed back to the system now. Under keep_freed_memory_for_reuse
// (the meshsal command's heap policy) the heap keeps what is freed, and each thread's
// heap keeps its own: memory one thread freed is not there for the next allocation of
// another, and the process's resident memory grows with every thread that worked. The
// tile store's ranks in threads are handed back so once done (their reading buffers).
#pragma once

namespace meshsal {

// glibc: malloc_trim(0) (every heap's free pages); elsewhere nothing.
void release_free_memory();

}  // namespace meshsal
