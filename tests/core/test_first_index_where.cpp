// first_index_where: the first offender, as a serial scan finds it.
#include <vector>

#include "core/first_index_where.h"
#include "test_util.h"

using namespace meshsal;

TEST_CASE("first_index_where: the smallest index that passes, whichever chunk finds one first", "[core]") {
  const size_t n = 3000000;  // many chunks of 2^18
  std::vector<uint8_t> bad(n, 0);
  CHECK(first_index_where(n, [&](size_t i) { return bad[i] != 0; }) == n);
  CHECK(first_index_where(0, [&](size_t) { return true; }) == 0);
  // Offenders late and early: the early one is named even where a later chunk ran first.
  bad[n - 1] = 1;
  CHECK(first_index_where(n, [&](size_t i) { return bad[i] != 0; }) == n - 1);
  bad[2500000] = bad[1700001] = bad[600000] = 1;
  CHECK(first_index_where(n, [&](size_t i) { return bad[i] != 0; }) == 600000);
  bad[262144] = 1;  // a chunk's first entry
  CHECK(first_index_where(n, [&](size_t i) { return bad[i] != 0; }) == 262144);
  bad[0] = 1;
  CHECK(first_index_where(n, [&](size_t i) { return bad[i] != 0; }) == 0);
}
