// Tiled simplification shared by processes (SimplifyOptions::exchange; issue 41): every
// rank gets the mesh one process makes, to the bit, in memory (simplify_mesh_tiled) and
// out of core (simplify_file: rank 0 writes the single-process bytes). The ranks run in
// threads exchanging through memory (thread_exchange.h), as MPI ranks do.
#include <filesystem>
#include <optional>
#include <vector>

#include "cli/synthetic.h"
#include "meshsal/meshsal.h"
#include "cli_run.h"
#include "out_of_core_util.h"
#include "test_simplify_util.h"
#include "test_util.h"
#include "thread_exchange.h"
#include "tiles/tile_rounds.h"

using namespace meshsal;
using namespace meshsal_test;

namespace {

SimplifyOptions ratio_tiles(double r, unsigned tiles) {
  SimplifyOptions o;
  o.ratio = r;
  o.tiles = tiles;
  o.threads = 1;
  return o;
}

void check_same(const Simplified& a, const Simplified& b) {
  CHECK(a.mesh.positions == b.mesh.positions);
  CHECK(a.mesh.triangles == b.mesh.triangles);
  CHECK(a.mesh.triangle_material == b.mesh.triangle_material);
  REQUIRE(a.mesh.attributes.size() == b.mesh.attributes.size());
  for (size_t k = 0; k < a.mesh.attributes.size(); ++k) {
    CHECK(a.mesh.attributes[k].name == b.mesh.attributes[k].name);
    CHECK(a.mesh.attributes[k].values == b.mesh.attributes[k].values);
  }
  CHECK(a.report.vertex_origin == b.report.vertex_origin);
  CHECK(a.report.collapses == b.report.collapses);
  CHECK(a.report.refused == b.report.refused);
  CHECK(a.report.error == b.report.error);
  CHECK(a.report.output_faces == b.report.output_faces);
}

}  // namespace

TEST_CASE("shared tiled simplification: every rank gets the single-process mesh", "[simplify][tiled][shared]") {
  struct Case {
    const char* name;
    Mesh mesh;
    SimplifyOptions options;
    bool weighted;
  };
  std::vector<Case> cases;
  // Meshes large enough that the first rounds keep several tiles (round_tiles): the groups
  // are shared, not all on rank 0.
  cases.push_back({"sphere 10% weighted", make_bumpy_sphere(5), ratio_tiles(0.1, 3), true});
  cases.push_back({"sphere 2% plain", make_bumpy_sphere(5), ratio_tiles(0.02, 4), false});
  cases.push_back({"plane attributes", simplify_test::attributed_plane(120), ratio_tiles(0.1, 4), false});
  for (const Case& c : cases) {
    const uint64_t faces = c.mesh.triangle_count();
    REQUIRE(detail::round_tiles(c.options.tiles, faces / 2) >= 3);
    std::vector<double> w;
    if (c.weighted) w = simplification_weights(c.mesh, weight_preset(Weighting::Balanced), cpu(Method::Exact)).weights;
    const Simplified single = simplify_mesh_tiled(c.mesh, c.options, w);
    REQUIRE(single.report.collapses > 0);
    for (int ranks : {2, 3, 5}) {
      std::vector<Simplified> got(static_cast<size_t>(ranks));
      run_ranks(ranks, [&](ThreadExchange& ex) {
        SimplifyOptions o = c.options;
        o.exchange = &ex;
        got[size_t(ex.rank())] = simplify_mesh_tiled(c.mesh, o, w);
      });
      for (int rank = 0; rank < ranks; ++rank) {
        INFO(c.name << ", ranks " << ranks << ", rank " << rank);
        check_same(single, got[size_t(rank)]);
      }
    }
  }
}

TEST_CASE("shared out-of-core simplification: rank 0 writes the single-process bytes", "[simplify][outofcore][shared]") {
  const auto dir = scratch_dir("shared_ooc_simplify");
  const std::string in = (dir / "in.ply").string();
  const Mesh mesh = make_bumpy_sphere(5);
  write_ply(in, mesh, {});
  REQUIRE(detail::round_tiles(3, mesh.triangle_count() / 2) == 3);  // the first round's groups are shared
  const SaliencyWeightOptions balanced = weight_preset(Weighting::Balanced);
  for (const bool weighted : {true, false}) {
    const std::optional<SaliencyWeightOptions> weights = weighted ? std::optional(balanced) : std::nullopt;
    OutOfCoreOptions ooc;
    ooc.temp_dir = dir.string();
    const std::string one = (dir / "one.ply").string();
    const OutOfCoreSimplifyReport single =
        simplify_file(in, one, ratio_tiles(0.1, 3), weights, cpu(Method::Fast), ooc);
    REQUIRE(single.simplify.collapses > 0);
    for (int ranks : {2, 3}) {
      INFO("weighted " << weighted << ", ranks " << ranks);
      const std::string shared = (dir / ("np" + std::to_string(ranks) + ".ply")).string();
      std::filesystem::remove(shared);
      std::vector<OutOfCoreSimplifyReport> got(static_cast<size_t>(ranks));
      run_ranks(ranks, [&](ThreadExchange& ex) {
        SimplifyOptions o = ratio_tiles(0.1, 3);
        o.exchange = &ex;
        got[size_t(ex.rank())] = simplify_file(in, shared, o, weights, cpu(Method::Fast), ooc);
      });
      CHECK(file_bytes(shared) == file_bytes(one));
      const OutOfCoreSimplifyReport& r = got[0];
      CHECK(r.saliency.ranks == ranks);
      CHECK(r.tiles == single.tiles);
      CHECK(r.simplify.collapses == single.simplify.collapses);
      CHECK(r.simplify.output_faces == single.simplify.output_faces);
      CHECK(r.simplify.error == single.simplify.error);
      if (weighted) CHECK(r.alpha == single.alpha);
      // Every rank agrees on what the passes did; the folder went with the run.
      for (const OutOfCoreSimplifyReport& x : got) CHECK(x.simplify.collapses == single.simplify.collapses);
      for (const auto& e : std::filesystem::directory_iterator(dir))
        CHECK(e.path().filename().string().rfind("meshsal-tiles-", 0) != 0);
    }
  }
}

TEST_CASE("simplify_file with a saliency output writes saliency_file's bytes from the same tiles",
          "[simplify][outofcore]") {
  const auto dir = scratch_dir("ooc_simplify_with_s");
  const std::string in = (dir / "in.ply").string();
  write_ply(in, make_bumpy_sphere(4), {});
  const SaliencyWeightOptions balanced = weight_preset(Weighting::Balanced);
  for (const Method method : {Method::Exact, Method::Fast}) {
    for (const bool weighted : {true, false}) {
      INFO("method " << int(method) << ", weighted " << weighted);
      const std::optional<SaliencyWeightOptions> weights = weighted ? std::optional(balanced) : std::nullopt;
      OutOfCoreOptions ooc;
      ooc.temp_dir = dir.string();
      ooc.memory_limit = uint64_t(1) << 30;
      ooc.dump_scales = true;
      const std::string s_alone = (dir / "s_alone.ply").string(), simplified_alone = (dir / "m_alone.ply").string();
      const OutOfCoreReport s = saliency_file(in, s_alone, cpu(method), ooc);
      simplify_file(in, simplified_alone, ratio_tiles(0.1, 2), weights, cpu(method), ooc);
      OutOfCoreOptions both = ooc;
      both.saliency_output = (dir / "s_both.ply").string();
      const OutOfCoreSimplifyReport r =
          simplify_file(in, (dir / "m_both.ply").string(), ratio_tiles(0.1, 2), weights, cpu(method), both);
      CHECK(file_bytes(dir / "s_both.ply") == file_bytes(s_alone));
      CHECK(file_bytes(dir / "m_both.ply") == file_bytes(simplified_alone));
      CHECK(r.saliency.saliency_max == s.saliency_max);
      CHECK(r.saliency.pairs > 0);
    }
  }
  // Both outputs to one file, and a saliency output that is the input, are refused.
  OutOfCoreOptions same;
  same.temp_dir = dir.string();
  same.saliency_output = (dir / "x.ply").string();
  CHECK_THROWS_WITH(simplify_file(in, same.saliency_output, ratio_tiles(0.1, 2), balanced, cpu(Method::Fast), same),
                    Catch::Contains("cannot both go to"));
  same.saliency_output = in;
  CHECK_THROWS(simplify_file(in, (dir / "y.ply").string(), ratio_tiles(0.1, 2), balanced, cpu(Method::Fast), same));
}
