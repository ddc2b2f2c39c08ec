// Tests: N processes in threads exchanging through memory (meshsal::TileExchange): what
// MPI ranks do, without MPI; and a helper that runs one body per rank.
#pragma once
#include <condition_variable>
#include <cstdint>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

#include "meshsal/meshsal.h"

namespace meshsal_test {

// N processes in threads, exchanging through memory: what MPI ranks do, without MPI.
class ThreadExchange : public meshsal::TileExchange {
 public:
  struct Shared {
    std::mutex m;
    std::condition_variable cv;
    int ranks = 0, arrived = 0;
    uint64_t round = 0;
    std::vector<std::vector<uint8_t>> slots, result;
  };
  ThreadExchange(Shared& s, int rank) : s_(s), rank_(rank) {}
  int rank() const override { return rank_; }
  int ranks() const override { return s_.ranks; }
  std::vector<std::vector<uint8_t>> all_gather(const std::vector<uint8_t>& mine) override {
    std::unique_lock<std::mutex> lock(s_.m);
    const uint64_t round = s_.round;
    s_.slots[rank_] = mine;
    if (++s_.arrived == s_.ranks) {
      s_.result = s_.slots;
      s_.arrived = 0;
      s_.round++;
      s_.cv.notify_all();
    } else {
      s_.cv.wait(lock, [&] { return s_.round != round; });
    }
    return s_.result;
  }

 private:
  Shared& s_;
  int rank_;
};

// body(exchange) once per rank, each in its own thread, all joined; then the first
// exception a rank threw, if any (a rank that throws before a collective the others wait
// in leaves them waiting: the test's timeout ends it).
inline void run_ranks(int ranks, const std::function<void(ThreadExchange&)>& body) {
  ThreadExchange::Shared shared;
  shared.ranks = ranks;
  shared.slots.resize(size_t(ranks));
  std::vector<std::exception_ptr> failed(static_cast<size_t>(ranks));
  std::vector<std::thread> threads;
  for (int rank = 0; rank < ranks; ++rank)
    threads.emplace_back([&, rank] {
      try {
        ThreadExchange ex(shared, rank);
        body(ex);
      } catch (...) {
        failed[size_t(rank)] = std::current_exception();
      }
    });
  for (auto& t : threads) t.join();
  for (const std::exception_ptr& e : failed)
    if (e) std::rethrow_exception(e);
}

}  // namespace meshsal_test
