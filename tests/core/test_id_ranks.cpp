// rank_ids against the plain way: sort, unique, and a binary search per entry.
#include <algorithm>
#include <catch2/catch.hpp>
#include <random>

#include "core/id_ranks.h"

using namespace meshsal;

TEST_CASE("rank_ids: distinct ids increasing and each entry's rank, as sort + unique + search", "[core]") {
  std::mt19937 rng(7);
  for (const size_t n : {size_t(0), size_t(1), size_t(5), size_t(1000), size_t(70000), size_t(300000)})
    for (const uint32_t max_id : {uint32_t(3), uint32_t(2047), uint32_t(5000000), uint32_t(UINT32_MAX)}) {
      std::uniform_int_distribution<uint32_t> pick(0, max_id);
      std::vector<uint32_t> ids(n);
      for (uint32_t& x : ids) x = pick(rng);
      std::vector<uint32_t> expect = ids;
      std::sort(expect.begin(), expect.end());
      expect.erase(std::unique(expect.begin(), expect.end()), expect.end());
      for (const unsigned threads : {1u, 2u}) {
        std::vector<uint32_t> distinct{99}, rank;
        rank_ids(ids.data(), n, max_id, distinct, rank, threads);
        REQUIRE(distinct == expect);
        REQUIRE(rank.size() == n);
        for (size_t i = 0; i < n; ++i)
          REQUIRE(rank[i] == size_t(std::lower_bound(expect.begin(), expect.end(), ids[i]) - expect.begin()));
      }
    }
}
