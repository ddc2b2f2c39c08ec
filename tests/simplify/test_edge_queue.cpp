// The simplifier's priority queue (bucket queue in front of a 4-ary heap) against a plain
// ordered multiset: same pops in the same order, with stale entries dropped on the way.
#include <catch2/catch.hpp>

#include <cmath>
#include <random>
#include <set>
#include <tuple>
#include <vector>

#include "simplify/edge_queue.h"

using namespace meshsal::detail;

namespace {

struct Less {
  bool operator()(const Entry& x, const Entry& y) const {
    return key_less(x, y) || (!key_less(y, x) && x.stamp < y.stamp);
  }
};

// Costs from several ranges at once: exact zeros, ties, and spans of many powers of two,
// so that entries land in the heap, in waiting buckets and below the current bucket.
float random_cost(std::mt19937& rng, float floor) {
  std::uniform_int_distribution<int> kind(0, 9);
  std::uniform_real_distribution<float> u(0.f, 1.f);
  switch (kind(rng)) {
    case 0: return 0.f;
    case 1: return 1.f;  // many exact ties, broken by (a, b)
    case 2: return floor * (1 + u(rng) * 0.01f);  // just above the last pop
    case 3: return floor * u(rng);                // below the last pop
    default: return std::ldexp(u(rng), std::uniform_int_distribution<int>(-30, 30)(rng));
  }
}

}  // namespace

TEST_CASE("edge queue pops in key order and drops stale entries like a sorted set",
          "[simplify]") {
  for (unsigned seed : {1u, 2u, 3u}) {
    std::mt19937 rng(seed);
    EdgeQueue q;
    std::multiset<Entry, Less> ref;
    std::vector<uint8_t> dead;  // by stamp, used here as the entry's id; dead stays dead
    const auto keep = [&](const Entry& e) { return !dead[e.stamp]; };
    std::uniform_int_distribution<uint32_t> vert(0, 40);  // few ids: ties on (cost, a)
    float last = 1.f;
    auto push = [&] {
      uint32_t a = vert(rng), b = vert(rng);
      if (a > b) std::swap(a, b);
      const Entry e{a, random_cost(rng, last), b, uint32_t(dead.size())};
      dead.push_back(0);
      q.push(e);
      ref.insert(e);
    };
    for (int i = 0; i < 3000; ++i) push();
    size_t popped = 0, filtered = 0;
    for (int step = 0; step < 20000; ++step) {
      const int op = std::uniform_int_distribution<int>(0, 99)(rng);
      if (op < 45) {
        push();
      } else if (op < 55) {  // some entry goes stale
        dead[std::uniform_int_distribution<size_t>(0, dead.size() - 1)(rng)] = 1;
      } else if (op == 55) {
        q.filter(keep);
        ++filtered;
        size_t live = 0;
        for (const Entry& e : ref) live += keep(e);
        REQUIRE(q.size() == live);
      } else {
        // The next live entry of each; stale ones the queue still holds are skipped.
        while (!ref.empty() && dead[ref.begin()->stamp]) ref.erase(ref.begin());
        Entry got{};
        bool any = false;
        while (q.ready(keep)) {
          got = q.pop();
          if (keep(got)) { any = true; break; }
        }
        REQUIRE(any == !ref.empty());
        if (!any) continue;
        const Entry want = *ref.begin();
        INFO("seed " << seed << " step " << step);
        // Entries with equal keys may come in either order: compare keys, then remove the
        // very entry that came out.
        REQUIRE(got.cost == want.cost);
        REQUIRE(got.a == want.a);
        REQUIRE(got.b == want.b);
        bool found = false;
        for (auto it = ref.begin(); it != ref.end() && !key_less(want, *it); ++it)
          if (it->stamp == got.stamp) { ref.erase(it); found = true; break; }
        REQUIRE(found);
        last = got.cost;
        ++popped;
      }
    }
    CHECK(popped > 5000);
    CHECK(filtered > 100);
    // Drain: everything left comes out in order.
    std::vector<std::tuple<float, uint32_t, uint32_t>> rest, want;
    while (q.ready(keep)) {
      const Entry e = q.pop();
      if (keep(e)) rest.emplace_back(e.cost, e.a, e.b);
    }
    for (const Entry& e : ref)
      if (keep(e)) want.emplace_back(e.cost, e.a, e.b);
    CHECK(rest.size() > 1000);
    CHECK(rest == want);
  }
}
