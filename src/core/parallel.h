// meshsal: a minimal parallel-for over index ranges with dynamic chunking.
#pragma once
#include <cstddef>
#include <functional>

namespace meshsal {

// Number of worker threads for a request: 0 means all hardware threads.
unsigned resolve_threads(unsigned requested);

// Calls body(begin, end) on disjoint chunks covering [0, n), from `threads` threads
// (0 = all cores). Chunks are handed out dynamically so uneven work balances.
// An exception thrown by body is rethrown on the calling thread.
void parallel_for(size_t n, unsigned threads, size_t chunk,
                  const std::function<void(size_t begin, size_t end)>& body);

}  // namespace meshsal
