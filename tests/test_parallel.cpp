// parallel_for: every index exactly once, and a thread that cannot be started (a process
// limit) means fewer threads, never std::terminate.
#include <atomic>
#include <mutex>
#include <set>
#include <system_error>
#include <vector>

#include "meshsal/parallel.h"
#include "test_util.h"

using namespace meshsal;

TEST_CASE("parallel_for runs on fewer threads when starting one fails", "[parallel]") {
  for (unsigned allowed : {0u, 1u, 3u}) {
    unsigned started = 0;
    ThreadStarter start = [&](std::function<void()> f) {
      if (started == allowed) throw std::system_error(std::make_error_code(std::errc::resource_unavailable_try_again));
      ++started;
      return std::thread(std::move(f));
    };
    std::vector<std::atomic<int>> hits(10000);
    std::mutex m;
    std::set<std::thread::id> ids;
    parallel_for(hits.size(), 8, 16, [&](size_t b, size_t e) {
      for (size_t i = b; i < e; ++i) hits[i]++;
      std::lock_guard<std::mutex> lock(m);
      ids.insert(std::this_thread::get_id());
    }, start);
    INFO("threads allowed besides the caller: " << allowed);
    CHECK(started == allowed);
    CHECK(ids.size() <= allowed + 1);
    size_t once = 0;
    for (auto& h : hits) once += h.load() == 1;
    CHECK(once == hits.size());
  }
}

TEST_CASE("parallel_for caps the thread count and rethrows the body's exception", "[parallel]") {
  CHECK(resolve_threads(5000) == kMaxThreads);
  CHECK(resolve_threads(3) == 3);
  CHECK(resolve_threads(0) >= 1);
  unsigned started = 0;
  ThreadStarter count = [&](std::function<void()> f) {
    ++started;
    return std::thread(std::move(f));
  };
  std::atomic<size_t> total{0};
  parallel_for(1 << 20, 100000, 64, [&](size_t b, size_t e) { total += e - b; }, count);
  CHECK(total == size_t(1) << 20);
  CHECK(started == kMaxThreads - 1);
  CHECK_THROWS_WITH(parallel_for(100, 4, 1, [](size_t, size_t) { throw std::runtime_error("boom"); }, count),
                    "boom");
}
