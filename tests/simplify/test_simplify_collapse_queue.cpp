// The simplifier's collapse queue (src/simplify/collapse_queue.h): refused edges wait at
// both ends, come back (once, and only while current) when either end's neighbourhood
// changes, and are forgotten with a vertex that collapsed away.
#include <catch2/catch.hpp>

#include <vector>

#include "simplify/collapse_queue.h"

using namespace meshsal::detail;

namespace {

std::vector<Entry> drain(CollapseQueue& q) {
  std::vector<Entry> out;
  const auto all = [](const Entry&) { return true; };
  while (q.edges().ready(all)) out.push_back(q.edges().pop());
  return out;
}

}  // namespace

TEST_CASE("collapse queue: refused edges come back once, when current", "[simplify]") {
  CollapseQueue q(6);
  std::vector<uint32_t> changed(6, 0);
  const auto current = [&](const Entry& e) { return changed[e.a] <= e.stamp && changed[e.b] <= e.stamp; };
  const Entry e01 = make_entry(1.0, 0, 1, 0), e12 = make_entry(2.0, 1, 2, 0), e34 = make_entry(0.5, 3, 4, 0);
  q.refuse(e01);
  q.refuse(e12);
  q.refuse(e34);
  CHECK(q.refused_at(1) == 2);
  CHECK(drain(q).empty());
  // Vertex 1's neighbourhood changed: both its edges come back, and leave vertex 0's and
  // 2's lists.
  q.release(1, current);
  CHECK(q.refused_at(0) == 0);
  CHECK(q.refused_at(2) == 0);
  std::vector<Entry> back = drain(q);
  REQUIRE(back.size() == 2);
  CHECK(back[0].b == 1);
  CHECK(back[1].b == 2);
  q.release(0, current);  // nothing left to release
  CHECK(drain(q).empty());
  // A stale refused edge (an end moved since) is dropped, not queued.
  changed[4] = 7;
  q.release(3, current);
  CHECK(drain(q).empty());
  CHECK(q.refused_at(4) == 0);
  // A vertex that collapsed away forgets its list.
  q.refuse(make_entry(1.0, 4, 5, 8));
  q.forget(5);
  CHECK(q.refused_at(5) == 0);
  CHECK(q.refused_at(4) == 1);
}

TEST_CASE("collapse queue: sweeps stale entries once it has doubled", "[simplify]") {
  CollapseQueue q(10000);
  for (uint32_t i = 0; i < 3000; ++i) q.push(make_entry(1.0 + i, i, i + 1, 0));
  q.start();  // next sweep above 2 * 3000 + 4096 entries
  std::vector<uint32_t> changed(10001, 0);
  const auto current = [&](const Entry& e) { return changed[e.a] <= e.stamp && changed[e.b] <= e.stamp; };
  for (uint32_t i = 0; i < 3000; ++i) changed[i] = 1;  // every entry so far is stale
  q.sweep_if_grown(current);
  CHECK(q.edges().size() == 3000);  // not yet
  for (uint32_t i = 0; i < 7100; ++i) q.push(make_entry(0.5, 3001 + (i % 6000), 3002 + (i % 6000), 1));
  q.sweep_if_grown(current);
  CHECK(q.edges().size() == 7100);
}
