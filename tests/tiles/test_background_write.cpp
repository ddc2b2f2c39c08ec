// BackgroundWrite (tiles/background_write.h): one write at a time, in the order submitted,
// and a failed write reported by the next submit or by finish, never lost silently.
#include <atomic>
#include <chrono>
#include <thread>
#include <vector>

#include "meshsal/meshsal.h"
#include "test_util.h"
#include "tiles/background_write.h"

using namespace meshsal;

TEST_CASE("background write: in order, one at a time, errors rethrown", "[tiles]") {
  SECTION("order and one at a time") {
    std::vector<int> done;
    std::atomic<int> running{0};
    {
      BackgroundWrite w;
      for (int i = 0; i < 6; ++i)
        w.submit([&, i] {
          CHECK(running.fetch_add(1) == 0);
          std::this_thread::sleep_for(std::chrono::milliseconds(i % 2 ? 5 : 0));
          done.push_back(i);
          running.fetch_sub(1);
        });
      w.finish();
      CHECK(done == std::vector<int>{0, 1, 2, 3, 4, 5});
    }
  }
  SECTION("a failed write: the next submit throws it, and does not start its own") {
    BackgroundWrite w;
    bool second = false;
    w.submit([] { throw Error("disk full"); });
    CHECK_THROWS_WITH(w.submit([&] { second = true; }), "disk full");
    w.finish();  // reported once
    CHECK_FALSE(second);
  }
  SECTION("a failed last write: finish throws it") {
    BackgroundWrite w;
    w.submit([] {});
    w.submit([] { throw Error("no space left"); });
    CHECK_THROWS_WITH(w.finish(), "no space left");
    CHECK_NOTHROW(w.finish());
  }
  SECTION("the destructor waits for the write under way") {
    std::atomic<bool> written{false};
    {
      BackgroundWrite w;
      w.submit([&] {
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
        written = true;
      });
    }
    CHECK(written);
  }
}
