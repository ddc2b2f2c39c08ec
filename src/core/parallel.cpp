#include "core/parallel.h"

#include "core/cancel.h"

#include <algorithm>
#include <atomic>
#include <exception>
#include <mutex>
#include <system_error>
#include <thread>
#include <vector>

namespace meshsal {

namespace {
std::atomic<unsigned> process_threads{0};
}  // namespace

void set_process_threads(unsigned threads) { process_threads.store(threads); }

unsigned resolve_threads(unsigned requested) {
  if (requested > 0) return std::min(requested, kMaxThreads);
  if (const unsigned share = process_threads.load(); share > 0) return std::min(share, kMaxThreads);
  unsigned hw = std::thread::hardware_concurrency();
  return hw > 0 ? std::min(hw, kMaxThreads) : 1;
}

void parallel_for(size_t n, unsigned threads, size_t chunk,
                  const std::function<void(size_t, size_t)>& body) {
  parallel_for(n, threads, chunk, body, [](std::function<void()> f) { return std::thread(std::move(f)); });
}

void parallel_for(size_t n, unsigned threads, size_t chunk,
                  const std::function<void(size_t, size_t)>& body, const ThreadStarter& start) {
  if (n == 0) return;
  if (chunk == 0) chunk = 1;
  // The caller's cancel flag, polled before every chunk on every thread (core/cancel.h).
  const std::atomic<bool>* cancel = current_cancel_flag();
  unsigned t = resolve_threads(threads);
  size_t chunks = (n + chunk - 1) / chunk;
  if (t > chunks) t = unsigned(chunks);
  if (t <= 1) {
    for (size_t begin = 0; begin < n; begin += chunk) {
      throw_if_cancelled();
      body(begin, std::min(n, begin + chunk));
    }
    return;
  }
  std::atomic<size_t> next{0};
  std::exception_ptr failure;
  std::mutex failure_mutex;
  auto worker = [&] {
    try {
      const CancelScope scope(cancel);  // nested library code on this worker polls it too
      for (;;) {
        size_t begin = next.fetch_add(chunk);
        if (begin >= n) break;
        throw_if_cancelled();
        body(begin, std::min(n, begin + chunk));
      }
    } catch (...) {
      std::lock_guard<std::mutex> lock(failure_mutex);
      if (!failure) failure = std::current_exception();
      next.store(n);  // stop handing out work
    }
  };
  std::vector<std::thread> pool;
  pool.reserve(t - 1);
  for (unsigned i = 1; i < t; ++i) {
    try {
      pool.push_back(start(worker));
    } catch (const std::system_error&) {
      break;  // no more threads to be had (EAGAIN): the ones running share the work
    }
  }
  worker();
  for (auto& th : pool) th.join();
  if (failure) std::rethrow_exception(failure);
}

void parallel_for_owned(size_t n, unsigned threads, const std::function<void(size_t, size_t)>& body) {
  // Ranges of at least 64K entries: each call scans the whole input, so more ranges than
  // that work needs only multiply the scans.
  const size_t ranges = std::max<size_t>(1, std::min<size_t>(resolve_threads(threads), n >> 16));
  parallel_for(ranges, unsigned(ranges), 1, [&](size_t begin, size_t end) {
    for (size_t r = begin; r < end; ++r) body(n * r / ranges, n * (r + 1) / ranges);
  });
}

}  // namespace meshsal
