// parallel_for: every index exactly once, and a thread that cannot be started (a process
// limit) means fewer threads, never std::terminate.
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <set>
#include <system_error>
#include <thread>
#include <vector>

#include "core/parallel.h"
#include "test_io_util.h"
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

TEST_CASE("parallel_for: a process's share of the cores is what 0 threads means", "[parallel]") {
  // Process-wide: restored whatever the checks say.
  struct Restore {
    ~Restore() { set_process_threads(0); }
  } restore;
  const unsigned all = resolve_threads(0);
  set_process_threads(3);
  CHECK(resolve_threads(0) == 3);
  CHECK(resolve_threads(5) == 5);  // an explicit count is kept
  std::mutex lock;
  std::set<std::thread::id> seen;
  parallel_for(1 << 12, 0, 1, [&](size_t, size_t) {
    std::this_thread::sleep_for(std::chrono::microseconds(20));
    std::lock_guard<std::mutex> hold(lock);
    seen.insert(std::this_thread::get_id());
  });
  CHECK(seen.size() <= 3);
  set_process_threads(1);
  CHECK(resolve_threads(0) == 1);
  set_process_threads(0);
  CHECK(resolve_threads(0) == all);
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

TEST_CASE("cli: saliency with more threads than the process may start falls back to fewer", "[parallel]") {
  // Under a 250 MB address-space limit a few dozen 8 MB thread stacks no longer fit: thread
  // starts fail with EAGAIN. The run must still succeed (it used to abort in std::terminate)
  // and write the same file as a one-thread run.
#if defined(__SANITIZE_ADDRESS__)
  // AddressSanitizer reserves terabytes of shadow address space at start: under any
  // `ulimit -v` the tool cannot even start, so this check only means something unsanitized.
  meshsal_test::skip_case("AddressSanitizer cannot run under an address-space limit");
  return;
#endif
  MESHSAL_REQUIRE_MESH(bunny, "bunny_36k.obj");
  const std::string dir = std::filesystem::temp_directory_path().string() + "/meshsal_threads_" +
                          std::to_string(::getpid());
  std::filesystem::create_directories(dir);
  meshsal_test::remove_at_exit(dir);
  const std::string cli = MESHSAL_CLI;
  const std::string many = "sh -c \"ulimit -v 250000; exec '" + cli + "' saliency '" + bunny + "' -o '" + dir +
                           "/many.ply' --threads 1000 --backend cpu -q\" 2>&1";
  const int rc = std::system(many.c_str());
  CHECK(WIFEXITED(rc));
  CHECK(WEXITSTATUS(rc) == 0);
  const std::string one = "'" + cli + "' saliency '" + bunny + "' -o '" + dir + "/one.ply' --threads 1 --backend cpu -q";
  REQUIRE(std::system(one.c_str()) == 0);
  std::ifstream a(dir + "/many.ply", std::ios::binary), b(dir + "/one.ply", std::ios::binary);
  const std::string sa((std::istreambuf_iterator<char>(a)), {}), sb((std::istreambuf_iterator<char>(b)), {});
  CHECK(sa.size() > 100000);
  CHECK(sa == sb);
  std::filesystem::remove_all(dir);
}
