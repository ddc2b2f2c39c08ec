// parallel_select: the serial loop's list, on any thread count.
#include <random>
#include <vector>

#include "core/parallel_select.h"
#include "test_util.h"

using namespace meshsal;

TEST_CASE("parallel_select: the entries that pass, in order, as the serial loop lists them", "[core]") {
  std::mt19937 rng(3);
  for (const size_t n : {size_t(0), size_t(1), size_t(1000), size_t(65536), size_t(300001)}) {
    std::vector<uint8_t> flag(n);
    for (uint8_t& f : flag) f = uint8_t(rng() % 3 == 0);
    std::vector<uint32_t> expect;
    for (size_t i = 0; i < n; ++i)
      if (flag[i]) expect.push_back(uint32_t(7 * i + 1));
    for (const unsigned threads : {1u, 2u, 5u}) {
      INFO(n << " entries, " << threads << " threads");
      std::vector<uint32_t> got{42};
      parallel_select(
          n, threads, [&](size_t i) { return flag[i] != 0; }, [](size_t i) { return uint32_t(7 * i + 1); }, got);
      CHECK(got == expect);
    }
  }
}
