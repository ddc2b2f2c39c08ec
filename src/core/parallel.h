// meshsal: a minimal parallel-for over index ranges with dynamic chunking.
#pragma once
#include <cstddef>
#include <functional>
#include <thread>

namespace meshsal {

// The most threads a request gets: more only costs memory and can exhaust a process limit.
constexpr unsigned kMaxThreads = 1024;

// Number of worker threads for a request: 0 means all hardware threads (or this process's
// share of them, below); capped at kMaxThreads.
unsigned resolve_threads(unsigned requested);

// The threads 0 stands for in this process from now on: a share of the cores where several
// processes share them (the command line under mpirun: the cores / the ranks on the
// machine), so that helpers called with 0 (the loader, masks, boxes) do not oversubscribe.
// 0 = all hardware threads again.
void set_process_threads(unsigned threads);

// Calls body(begin, end) on disjoint chunks covering [0, n), from `threads` threads
// (0 = all cores). Chunks are handed out dynamically so uneven work balances.
// An exception thrown by body is rethrown on the calling thread. A thread that cannot be
// started (a process limit) is not an error: the loop runs on the threads it has, at
// worst on the calling thread alone.
void parallel_for(size_t n, unsigned threads, size_t chunk,
                  const std::function<void(size_t begin, size_t end)>& body);

// Splits [0, n) into one contiguous range per thread and calls body(lo, hi) once per range,
// concurrently. For scatter loops (over the triangles, adding into per-vertex sums) where
// each call reads all the input but writes only the entries of its own range: every entry
// is then summed in input order whatever the thread count, so the results are the same bits
// on 1 thread or 64.
void parallel_for_owned(size_t n, unsigned threads, const std::function<void(size_t lo, size_t hi)>& body);

// The same with the way a thread is started given (tests make it fail): `start` returns a
// running std::thread or throws std::system_error.
using ThreadStarter = std::function<std::thread(std::function<void()>)>;
void parallel_for(size_t n, unsigned threads, size_t chunk,
                  const std::function<void(size_t begin, size_t end)>& body, const ThreadStarter& start);

}  // namespace meshsal
