#include "tiles/thread_ranks.h"

#include "core/cancel.h"

#include <atomic>
#include <condition_variable>
#include <string>
#include <system_error>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace meshsal {

namespace {

// What the ranks left waiting are told; run_thread_ranks passes on the failure behind it.
constexpr const char* kOtherRankFailed = "another rank of this process failed";

struct Shared {
  std::mutex m;
  std::condition_variable cv;
  int ranks = 0, arrived = 0;
  uint64_t round = 0;
  bool broken = false;  // a rank ended by an exception: no collective can complete
  std::vector<std::vector<uint8_t>> slots, result;
  // No collective can complete any more: every rank waiting in one is woken to fail.
  void break_all() {
    const std::lock_guard<std::mutex> lock(m);
    broken = true;
    cv.notify_all();
  }
};

class ThreadRank final : public TileExchange {
 public:
  ThreadRank(Shared& s, int rank) : s_(s), rank_(rank) {}
  int rank() const override { return rank_; }
  int ranks() const override { return s_.ranks; }
  std::vector<std::vector<uint8_t>> all_gather(const std::vector<uint8_t>& mine) override { return exchange(mine, -1); }
  // Only the root copies every rank's bytes out (the others' copies would multiply a
  // histogram by the thread count).
  std::vector<std::vector<uint8_t>> gather(const std::vector<uint8_t>& mine, int root) override {
    return exchange(mine, root);
  }

 private:
  // Every rank's bytes to every rank (root -1) or to `root` alone.
  std::vector<std::vector<uint8_t>> exchange(const std::vector<uint8_t>& mine, int root) {
    std::unique_lock<std::mutex> lock(s_.m);
    if (s_.broken) throw Error(kOtherRankFailed);
    const uint64_t round = s_.round;
    s_.slots[size_t(rank_)] = mine;
    if (++s_.arrived == s_.ranks) {
      s_.result = std::move(s_.slots);  // (each waiting rank copies it before a next round can start)
      s_.slots.assign(size_t(s_.ranks), {});
      s_.arrived = 0;
      s_.round++;
      s_.cv.notify_all();
    } else {
      s_.cv.wait(lock, [&] { return s_.round != round || s_.broken; });
      if (s_.round == round) throw Error(kOtherRankFailed);
    }
    if (root >= 0 && root != rank_) return {};
    return s_.result;
  }

  Shared& s_;
  int rank_;
};

}  // namespace

void run_thread_ranks(int ranks, const std::function<void(TileExchange&)>& body) {
  Shared shared;
  shared.ranks = ranks;
  shared.slots.resize(size_t(ranks));
  std::vector<std::exception_ptr> failed(static_cast<size_t>(ranks));
  std::vector<std::thread> threads;
  auto run = [&](int rank) {
    try {
      ThreadRank ex(shared, rank);
      body(ex);
    } catch (...) {
      failed[size_t(rank)] = std::current_exception();
      shared.break_all();
    }
  };
  const std::atomic<bool>* cancel = current_cancel_flag();  // polled on every rank's thread too
  try {
    for (int rank = 1; rank < ranks; ++rank)
      threads.emplace_back([&, rank] {
        const CancelScope scope(cancel);
        run(rank);
      });
  } catch (const std::system_error&) {  // no thread to be had: the ranks started cannot finish
    shared.break_all();
    for (auto& t : threads) t.join();
    throw Error("cannot start a thread for each of " + std::to_string(ranks) + " ranks");
  }
  run(0);  // rank 0 on the calling thread (its progress is the caller's)
  for (auto& t : threads) t.join();
  // The first failure that is not the others' "another rank failed".
  std::exception_ptr first;
  for (const std::exception_ptr& e : failed) {
    if (!e) continue;
    try {
      std::rethrow_exception(e);
    } catch (const Error& err) {
      if (std::string(err.what()) == kOtherRankFailed) {
        if (!first) first = e;
        continue;
      }
      std::rethrow_exception(e);
    } catch (...) {
      std::rethrow_exception(e);
    }
  }
  if (first) std::rethrow_exception(first);
}

}  // namespace meshsal
