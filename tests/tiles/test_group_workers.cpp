// A tiled simplification pass's groups side by side (tiles/group_workers.h, issue 41): every
// group once, the largest first, an error stops the rest; and the meshes and files come
// out the same on 1 thread or several, alone, shared by ranks, and out of core under a
// limit that holds several pieces at once.
#include <algorithm>
#include <atomic>
#include <chrono>
#include <thread>
#include <filesystem>
#include <mutex>
#include <optional>
#include <set>
#include <stdexcept>
#include <vector>

#include "cli/synthetic.h"
#include "cli_run.h"
#include "meshsal/meshsal.h"
#include "out_of_core_util.h"
#include "test_simplify_util.h"
#include "test_util.h"
#include "thread_exchange.h"
#include "tiles/group_workers.h"

using namespace meshsal;
using namespace meshsal::detail;
using namespace meshsal_test;

namespace {

SimplifyOptions tiled(double ratio, unsigned tiles, unsigned threads) {
  SimplifyOptions o;
  o.ratio = ratio;
  o.tiles = tiles;
  o.threads = threads;
  return o;
}

void check_same(const Simplified& a, const Simplified& b) {
  CHECK(a.mesh.positions == b.mesh.positions);
  CHECK(a.mesh.triangles == b.mesh.triangles);
  REQUIRE(a.mesh.attributes.size() == b.mesh.attributes.size());
  for (size_t k = 0; k < a.mesh.attributes.size(); ++k) CHECK(a.mesh.attributes[k].values == b.mesh.attributes[k].values);
  CHECK(a.report.vertex_origin == b.report.vertex_origin);
  CHECK(a.report.collapses == b.report.collapses);
  CHECK(a.report.refused == b.report.refused);
  CHECK(a.report.error == b.report.error);
}

// A TileExchange that is never asked anything: rank `rank` of `ranks` (runs_group's share).
class ShareOnly final : public TileExchange {
 public:
  ShareOnly(int rank, int ranks) : rank_(rank), ranks_(ranks) {}
  int rank() const override { return rank_; }
  int ranks() const override { return ranks_; }
  std::vector<std::vector<uint8_t>> all_gather(const std::vector<uint8_t>&) override {
    throw std::logic_error("not asked");
  }

 private:
  int rank_, ranks_;
};

}  // namespace

TEST_CASE("group workers: one per thread, as many as the pieces the limit holds", "[tiles][simplify]") {
  CHECK(group_workers(4, 0, 10).workers == 4);
  CHECK(group_workers(4, 0, 10).inner == 1);
  CHECK(group_workers(4, 2, 10).workers == 2);  // the limit holds two pieces
  CHECK(group_workers(4, 2, 10).inner == 2);    // each group's own steps take the rest
  CHECK(group_workers(4, 0, 1).workers == 1);   // one group: it has every thread
  CHECK(group_workers(4, 0, 1).inner == 4);
  CHECK(group_workers(4, 0, 0).workers == 1);
  CHECK(group_workers(1, 8, 10).workers == 1);
}

TEST_CASE("for_each_group: every group of this process once, the largest first, errors stop it", "[tiles][simplify]") {
  const std::vector<size_t> sizes = {5, 90, 1, 40, 40, 7, 300};
  SECTION("one worker: by size, the larger index after an equal one") {
    std::vector<size_t> order;
    for_each_group(nullptr, sizes, 1, [&](size_t g, unsigned worker) {
      CHECK(worker == 0);
      order.push_back(g);
    });
    CHECK(order == std::vector<size_t>{6, 1, 3, 4, 5, 0, 2});
  }
  SECTION("three workers: each group once, never more than three at a time") {
    std::mutex m;
    std::multiset<size_t> seen;
    std::atomic<int> busy{0};
    int most = 0;
    for_each_group(nullptr, sizes, 3, [&](size_t g, unsigned worker) {
      REQUIRE(worker < 3);
      const int now = ++busy;
      std::this_thread::sleep_for(std::chrono::milliseconds(2));
      {
        const std::lock_guard<std::mutex> lock(m);
        seen.insert(g);
        most = std::max(most, now);
      }
      --busy;
    });
    CHECK(seen == std::multiset<size_t>{0, 1, 2, 3, 4, 5, 6});
    CHECK(most <= 3);
  }
  SECTION("shared: rank 1 of 3 runs groups 1 and 4 alone") {
    ShareOnly ex(1, 3);
    std::vector<size_t> order;
    for_each_group(&ex, sizes, 1, [&](size_t g, unsigned) { order.push_back(g); });
    CHECK(order == std::vector<size_t>{1, 4});
  }
  SECTION("a group that throws: rethrown here, no group started after it") {
    std::atomic<int> started{0};
    CHECK_THROWS_WITH(for_each_group(nullptr, sizes, 1,
                                     [&](size_t g, unsigned) {
                                       ++started;
                                       if (g == 1) throw Error("group 1 failed");
                                     }),
                      "group 1 failed");
    CHECK(started == 2);  // group 6, then group 1
  }
}

TEST_CASE("tiled simplify: the groups side by side give the one-thread mesh", "[simplify][tiled]") {
  const Mesh sphere = make_bumpy_sphere(5);
  const std::vector<double> w =
      simplification_weights(sphere, weight_preset(Weighting::Balanced), cpu(Method::Fast)).weights;
  const Mesh plane = simplify_test::attributed_plane(120);
  struct Case {
    const char* name;
    const Mesh& mesh;
    double ratio;
    unsigned tiles;
    std::vector<double> weights;
  };
  for (const Case& c : {Case{"sphere 10% weighted", sphere, 0.1, 3, w}, Case{"sphere 2% plain", sphere, 0.02, 4, {}},
                        Case{"plane with attributes", plane, 0.1, 4, {}}}) {
    const Simplified one = simplify_mesh_tiled(c.mesh, tiled(c.ratio, c.tiles, 1), c.weights);
    REQUIRE(one.report.collapses > 0);
    for (unsigned threads : {2u, 3u, 8u}) {
      INFO(c.name << ", " << threads << " threads");
      check_same(one, simplify_mesh_tiled(c.mesh, tiled(c.ratio, c.tiles, threads), c.weights));
    }
    // Shared by two ranks, each running its groups on three threads.
    std::vector<Simplified> got(2);
    run_ranks(2, [&](ThreadExchange& ex) {
      SimplifyOptions o = tiled(c.ratio, c.tiles, 3);
      o.exchange = &ex;
      got[size_t(ex.rank())] = simplify_mesh_tiled(c.mesh, o, c.weights);
    });
    INFO(c.name << ", 2 ranks of 3 threads");
    check_same(one, got[0]);
    check_same(one, got[1]);
  }
}

TEST_CASE("out-of-core simplify: the groups side by side under a limit, the one-thread bytes", "[outofcore][simplify]") {
  const auto dir = scratch_dir("ooc_group_workers");
  const std::string in = (dir / "plane.ply").string();
  write_ply(in, make_plane_with_bump(2.0, 300, 0.3, 0.2), {});  // 90,601 vertices
  OutOfCoreOptions ooc;
  ooc.temp_dir = dir.string();
  ooc.memory_limit = uint64_t(60) << 20;
  const std::string one = (dir / "one.ply").string(), many = (dir / "many.ply").string();
  for (const bool weighted : {false, true}) {
    INFO("weighted " << weighted);
    const std::optional<SaliencyWeightOptions> weights =
        weighted ? std::optional(weight_preset(Weighting::Balanced)) : std::nullopt;
    const OutOfCoreSimplifyReport r1 = simplify_file(in, one, tiled(0.05, 1, 1), weights, cpu(Method::Fast), ooc);
    const OutOfCoreSimplifyReport r4 = simplify_file(in, many, tiled(0.05, 1, 4), weights, cpu(Method::Fast), ooc);
    CHECK(r1.groups_at_once == 1);
    CHECK(r4.groups_at_once == 4);  // the limit holds a piece per thread
    // The tiles do not depend on the threads (the limit sizes them for four pieces at once),
    // so neither do the bytes.
    CHECK(r1.tiles == r4.tiles);
    CHECK(r1.tiles > 1);
    CHECK(file_bytes(one) == file_bytes(many));
    CHECK(r1.simplify.collapses == r4.simplify.collapses);
    CHECK(r4.simplify.collapses > 0);
  }
}
