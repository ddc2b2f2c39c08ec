// run_thread_ranks (tiles/thread_ranks.h): ranks in threads exchange through memory, and a
// rank that fails ends the others' waits instead of leaving them in a collective forever.
#include <atomic>
#include <new>
#include <string>
#include <vector>

#include "meshsal/meshsal.h"
#include "test_util.h"
#include "tiles/thread_ranks.h"

using namespace meshsal;

TEST_CASE("thread ranks: every rank's bytes in rank order, a failure rethrown, no wait left", "[tiles]") {
  std::vector<std::vector<std::vector<uint8_t>>> got(3);
  run_thread_ranks(3, [&](TileExchange& ex) {
    CHECK(ex.ranks() == 3);
    got[size_t(ex.rank())] = ex.all_gather({uint8_t(ex.rank()), 7});
    ex.all_gather({});  // a second round
  });
  for (const auto& g : got) CHECK(g == std::vector<std::vector<uint8_t>>{{0, 7}, {1, 7}, {2, 7}});
  // Rank 2 fails before the collective the others wait in: theirs throws, and the call
  // rethrows rank 2's own exception (not the others' "another rank failed").
  std::atomic<int> woke{0};
  CHECK_THROWS_AS(run_thread_ranks(3,
                                   [&](TileExchange& ex) {
                                     if (ex.rank() == 2) throw std::bad_alloc();
                                     try {
                                       ex.all_gather({1});
                                     } catch (const Error&) {
                                       ++woke;
                                       throw;
                                     }
                                   }),
                  std::bad_alloc);
  CHECK(woke == 2);
  CHECK_THROWS_WITH(run_thread_ranks(2, [](TileExchange& ex) {
                      if (ex.rank() == 1) throw Error("rank 1's reason");
                      ex.all_gather({});
                    }),
                    "rank 1's reason");
}
