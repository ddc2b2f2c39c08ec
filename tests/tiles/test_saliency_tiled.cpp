// Tiled saliency (SaliencyOptions::tiles, saliency_tiles.h) against the untiled run: the
// exact method bit for bit, the fast method to 1e-4 of each map's maximum.
#include <cmath>
#include <condition_variable>
#include <mutex>
#include <random>
#include <thread>

#include "cli/synthetic.h"
#include "core/mesh_points.h"
#include "saliency/gaussian_filter_fast.h"
#include "saliency/saliency.h"
#include "saliency/sparse_cells.h"
#include "tiles/saliency_tiles.h"
#include "tiles/tile_reduce.h"
#include "test_util.h"
#include "thread_exchange.h"

using namespace meshsal;
using namespace meshsal_test;

namespace {

SaliencyOptions cpu_options(Method method, bool smoothed) {
  SaliencyOptions o;
  o.method = method;
  o.smoothed = smoothed;
  o.backend = Backend::Cpu;
  return o;
}

// Largest |a - b| relative to max |a|, over one map.
double map_error(const std::vector<double>& a, const std::vector<double>& b) { return meshsal_test::rel_error(a, b); }

// Every map of a tiled run equals the untiled one's, bit for bit.
void check_identical(const SaliencyResult& whole, const SaliencyResult& tiled) {
  CHECK(tiled.eps == whole.eps);
  CHECK(tiled.is_point == whole.is_point);
  CHECK(tiled.curvature == whole.curvature);
  REQUIRE(tiled.raw.size() == whole.raw.size());
  for (size_t k = 0; k < whole.raw.size(); ++k) {
    INFO("scale " << k << " error " << map_error(whole.raw[k], tiled.raw[k]));
    CHECK(tiled.raw[k] == whole.raw[k]);
  }
  INFO("saliency error " << map_error(whole.saliency, tiled.saliency));
  CHECK(tiled.saliency == whole.saliency);
  INFO("smoothed error " << (whole.smoothed.empty() ? 0.0 : map_error(whole.smoothed, tiled.smoothed)));
  CHECK(tiled.smoothed == whole.smoothed);
}

// A bumpy sphere beside a plane with a bump, far apart: tiles between them hold no vertex.
Mesh two_parts() {
  Mesh a = make_bumpy_sphere(3);
  Mesh b = make_plane_with_bump(2.0, 40, 0.3, 0.2);
  const uint32_t base = uint32_t(a.vertex_count());
  for (size_t v = 0; v < b.vertex_count(); ++v) {
    a.positions.push_back(b.positions[3 * v] + 9.0f);
    a.positions.push_back(b.positions[3 * v + 1]);
    a.positions.push_back(b.positions[3 * v + 2]);
  }
  for (uint32_t i : b.triangles) a.triangles.push_back(i + base);
  return a;
}

// A single-process run of the phases with a plan the caller may change (the halo tests).
SaliencyResult run_phases(const Mesh& mesh, TilePlan plan) {
  SaliencyResult r;
  r.is_point = referenced_vertices(mesh);
  const size_t n = mesh.vertex_count();
  const TileBuckets buckets = bucket_triangles(mesh, plan);
  const TileSource source = memory_tile_source(mesh, buckets);
  std::vector<TilePoints> points;
  std::vector<TileQuery> queries;
  for (size_t t = 0; t < tile_count(plan); ++t) {
    TileCurvature c = tile_curvature(plan, t, source);
    points.push_back(std::move(c.points));
    queries.push_back(std::move(c.query));
  }
  const TilePointSource point_source = memory_point_source(points);
  std::vector<TileRaw> raws;
  std::vector<ScaleMax> max(plan.scales.size());
  for (size_t t = 0; t < tile_count(plan); ++t) {
    raws.push_back(tile_raw_maps(plan, t, queries[t], point_source));
    merge_scale_max(max, tile_scale_max(raws.back()));
  }
  std::vector<double> mbar;
  for (size_t k = 0; k < plan.scales.size(); ++k) {
    std::vector<LocalMax> all;
    for (const TileRaw& raw : raws) {
      auto m = tile_local_maxima(raw.candidates, max);
      all.insert(all.end(), m[k].begin(), m[k].end());
    }
    mbar.push_back(mbar_of(all, max[k]));
  }
  r.saliency.assign(n, 0.0);
  r.raw.assign(plan.scales.size(), std::vector<double>(n, 0.0));
  for (const TileRaw& raw : raws) {
    TileResult t = tile_finish(raw, plan, max, mbar);
    for (size_t i = 0; i < t.global.size(); ++i) {
      r.saliency[t.global[i]] = t.saliency[i];
      for (size_t k = 0; k < t.raw.size(); ++k) r.raw[k][t.global[i]] = t.raw[k][i];
    }
  }
  return r;
}

TilePlan plan_for(const Mesh& mesh, const SaliencyOptions& o, unsigned tiles) {
  const std::vector<uint8_t> is_point = referenced_vertices(mesh);
  uint64_t points = 0;
  for (uint8_t f : is_point) points += f;
  return make_tile_plan(mesh_points_bbox(mesh, is_point), points, o, tiles);
}

}  // namespace

TEST_CASE("tiled exact saliency is bit-identical to the untiled run", "[tiles]") {
  const Mesh meshes[] = {make_bumpy_sphere(4), make_plane_with_bump(2.0, 60, 0.3, 0.2), make_cube(12)};
  for (const Mesh& mesh : meshes)
    for (bool smoothed : {false, true}) {
      SaliencyOptions o = cpu_options(Method::Exact, smoothed);
      const SaliencyResult whole = compute_saliency(mesh, o);
      for (unsigned tiles : {2u, 3u, 7u}) {
        INFO("vertices " << mesh.vertex_count() << " tiles " << tiles << " smoothed " << smoothed);
        o.tiles = tiles;
        const SaliencyResult tiled = compute_saliency(mesh, o);
        CHECK(tiled.tiles == size_t(plan_for(mesh, o, tiles).tiles[0]) * plan_for(mesh, o, tiles).tiles[1] *
                                 plan_for(mesh, o, tiles).tiles[2]);
        CHECK(tiled.tiles > 1);
        check_identical(whole, tiled);
        // The halo's work: every tile sweeps its queries, more than the whole run's once.
        CHECK(tiled.pairs > whole.pairs);
      }
    }
}

// The fast method's cells, query grids and float sums are laid over the whole mesh's frame
// (a tile's are windows of the whole mesh's), so the raw maps come out bit for bit; S is
// the same maps suppressed and added in another order (the whole mesh's pipeline sums them
// chain by chain: 2, 4, 3, 6, 5), equal to rounding, and the smoothed Sm filters those S
// values (a cell's float sum of S may round one float step apart: 8e-9 of Sm on bunny_36k).
void check_fast_tiles(const SaliencyResult& whole, const SaliencyResult& tiled) {
  CHECK(tiled.curvature == whole.curvature);
  REQUIRE(tiled.raw.size() == whole.raw.size());
  for (size_t k = 0; k < whole.raw.size(); ++k) {
    INFO("scale " << k << " error " << map_error(whole.raw[k], tiled.raw[k]));
    CHECK(tiled.raw[k] == whole.raw[k]);
  }
  CHECK(map_error(whole.saliency, tiled.saliency) <= 1e-15);
  if (!whole.smoothed.empty()) CHECK(map_error(whole.smoothed, tiled.smoothed) <= 1e-7);
}

TEST_CASE("tiled fast saliency equals the untiled run: the raw maps bit for bit", "[tiles]") {
  const Mesh meshes[] = {make_bumpy_sphere(4), make_plane_with_bump(2.0, 60, 0.3, 0.2)};
  for (const Mesh& mesh : meshes)
    for (bool smoothed : {false, true}) {
      SaliencyOptions o = cpu_options(Method::Fast, smoothed);
      const SaliencyResult whole = compute_saliency(mesh, o);
      for (unsigned tiles : {2u, 5u}) {
        INFO("vertices " << mesh.vertex_count() << " tiles " << tiles << " smoothed " << smoothed);
        o.tiles = tiles;
        check_fast_tiles(whole, compute_saliency(mesh, o));
      }
    }
}

// Phase 1 tests each own point against its ring from the bucket's triangles: a point whose
// only triangle is degenerate (v, v, v) has an empty ring and is a local maximum, a corner
// repeated in a triangle is no neighbour of itself, as in the whole mesh's adjacency.
TEST_CASE("tiled saliency: degenerate triangles and empty rings as the untiled run", "[tiles]") {
  Mesh mesh = make_bumpy_sphere(4);
  const uint32_t n = uint32_t(mesh.vertex_count());
  // A lone point beside the sphere, its only triangle (v, v, v), and a triangle of the sphere
  // with a corner twice.
  for (float c : {0.3f, 0.2f, 0.1f}) mesh.positions.push_back(c);
  for (uint32_t k = 0; k < 3; ++k) mesh.triangles.push_back(n);
  const uint32_t a = mesh.triangles[0], b = mesh.triangles[1];
  for (uint32_t v : {a, a, b}) mesh.triangles.push_back(v);
  for (Method method : {Method::Exact, Method::Fast}) {
    SaliencyOptions o = cpu_options(method, false);
    const SaliencyResult whole = compute_saliency(mesh, o);
    REQUIRE(whole.is_point[n] == 1);
    for (unsigned tiles : {2u, 4u}) {
      INFO("method " << int(method) << " tiles " << tiles);
      o.tiles = tiles;
      const SaliencyResult tiled = compute_saliency(mesh, o);
      if (method == Method::Exact) check_identical(whole, tiled);
      else check_fast_tiles(whole, tiled);
    }
  }
}

TEST_CASE("tiled saliency on shared scans with tiny tiles", "[tiles][data]") {
  for (const char* name : {"bunny_36k.obj", "fandisk_6k.obj"}) {
    MESHSAL_MESH_OR_CONTINUE(path, name);
    const Mesh mesh = load_mesh(path);
    INFO(name);
    SaliencyOptions exact = cpu_options(Method::Exact, true);
    const SaliencyResult whole = compute_saliency(mesh, exact);
    exact.tiles = 6;
    check_identical(whole, compute_saliency(mesh, exact));

    SaliencyOptions fast = cpu_options(Method::Fast, true);
    const SaliencyResult fast_whole = compute_saliency(mesh, fast);
    fast.tiles = 6;
    check_fast_tiles(fast_whole, compute_saliency(mesh, fast));
  }
}

TEST_CASE("tiles holding no vertex and a mesh in one tile", "[tiles]") {
  const Mesh mesh = two_parts();
  SaliencyOptions o = cpu_options(Method::Exact, true);
  const SaliencyResult whole = compute_saliency(mesh, o);
  o.tiles = 9;
  const TilePlan plan = plan_for(mesh, o, 9);
  // Some tiles between the parts are empty.
  size_t empty = 0;
  std::vector<uint8_t> used(tile_count(plan), 0);
  for (size_t v = 0; v < mesh.vertex_count(); ++v) used[tile_of(plan, &mesh.positions[3 * v])] = 1;
  for (uint8_t u : used) empty += u ? 0 : 1;
  CHECK(empty >= 3);
  check_identical(whole, compute_saliency(mesh, o));

  // One tile (the tiled path forced by an exchange of one process): the whole mesh.
  SaliencyResult r;
  run_ranks(1, [&](ThreadExchange& one) {
    SaliencyOptions single = cpu_options(Method::Exact, true);
    single.exchange = &one;
    r = compute_saliency(mesh, single);
  });
  CHECK(r.tiles == 1);
  check_identical(whole, r);
}

TEST_CASE("the halo is as wide as the filter reaches and no narrower", "[tiles]") {
  const Mesh mesh = make_bumpy_sphere(5);
  const SaliencyOptions o = cpu_options(Method::Exact, false);
  const SaliencyResult whole = compute_saliency(mesh, o);
  TilePlan plan = plan_for(mesh, o, 4);
  const double cutoff = 2 * 12 * plan.eps;  // the largest sigma's cutoff, default scales
  CHECK(plan.source_margin > cutoff);
  CHECK(plan.source_margin < cutoff * 1.6);
  // The plan's halo: the same bits.
  const SaliencyResult full = run_phases(mesh, plan);
  CHECK(full.saliency == whole.saliency);
  // A quarter narrower than the cutoff: points within reach go missing and the maps change.
  plan.source_margin = 0.75 * cutoff;
  const SaliencyResult narrow = run_phases(mesh, plan);
  double worst = 0;
  for (size_t k = 0; k < whole.raw.size(); ++k) worst = std::max(worst, map_error(whole.raw[k], narrow.raw[k]));
  CHECK(worst > 1e-6);
}

TEST_CASE("tiles shared by processes through an exchange give the single-process result", "[tiles]") {
  const Mesh mesh = make_bumpy_sphere(4);
  for (Method method : {Method::Exact, Method::Fast}) {
    SaliencyOptions o = cpu_options(method, true);
    o.tiles = 3;
    o.threads = 1;
    const SaliencyResult single = compute_saliency(mesh, o);
    for (int ranks : {2, 3}) {
      std::vector<SaliencyResult> results(ranks);
      run_ranks(ranks, [&](ThreadExchange& ex) {
        SaliencyOptions mine = o;
        mine.exchange = &ex;
        results[size_t(ex.rank())] = compute_saliency(mesh, mine);
      });
      for (int rank = 0; rank < ranks; ++rank) {
        INFO("ranks " << ranks << " rank " << rank);
        CHECK(results[rank].ranks == ranks);
        CHECK(results[rank].pairs == single.pairs);
        check_identical(single, results[rank]);
      }
    }
  }
}

TEST_CASE("tiles: bad options are clear errors", "[tiles]") {
  const Mesh mesh = make_sphere(1.0, 2);
  SaliencyOptions o = cpu_options(Method::Exact, false);
  o.tiles = kMaxTiles + 1;
  CHECK_THROWS_WITH(compute_saliency(mesh, o), Catch::Contains("tiles must be at most"));
  o.tiles = 2;
  o.backend = Backend::Gpu;
  CHECK_THROWS_WITH(compute_saliency(mesh, o), Catch::Contains("tiles run on the CPU"));
}

TEST_CASE("phase 0: the tiles' inner cells and their shared ones count the whole mesh's cells", "[tiles][fast]") {
  // Every occupied cell once: inside one tile (counted there) or reaching across a face
  // (merged over the tiles that hold points in it); the whole mesh's count_fast_cells is
  // the oracle, at coarse and tiny tiles (cells wider than a tile).
  Mesh m = make_bumpy_sphere(4);
  const std::vector<uint8_t> all(m.vertex_count(), 1);
  const BoundingBox box = mesh_points_bbox(m, all);
  for (const unsigned tiles : {1u, 2u, 3u, 7u, 40u}) {
    INFO(tiles << " tiles");
    SaliencyOptions o = cpu_options(Method::Fast, true);
    const TilePlan plan = make_tile_plan(box, m.vertex_count(), o, tiles);
    const std::vector<uint64_t> expect = count_fast_cells(m, all, all, box, tile_cell_sigmas(plan));
    const TileBuckets buckets = bucket_triangles(m, plan);
    const TileSource source = memory_tile_source(m, buckets);
    TileCells cells = tile_cells(plan, 0, TilePoints{});
    size_t across = 0;
    for (size_t t = 0; t < tile_count(plan); ++t) {
      const TileCells c = tile_cells(plan, t, tile_curvature(plan, t, source).points);
      for (const auto& keys : c.across) {
        CHECK(std::is_sorted(keys.begin(), keys.end()));
        across += keys.size();
      }
      add_tile_cells(cells, c);
    }
    CHECK(whole_mesh_cells(nullptr, cells) == expect);
    if (tiles == 1) CHECK(across == 0);
    if (tiles >= 3) CHECK(across > 0);
  }
}

TEST_CASE("distinct cell keys: the bitmap's keys are the sort's", "[tiles][fast]") {
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u(-1.f, 1.f);
  for (const size_t n : {size_t(1), size_t(50), size_t(20000)}) {
    std::vector<float> xyz(3 * n);
    for (float& x : xyz) x = u(rng) * u(rng);  // denser near the middle
    BoundingBox box;
    for (int a = 0; a < 3; ++a) box.min[a] = -1, box.max[a] = 1;
    BoundingBox within = box;
    for (int a = 0; a < 3; ++a) within.min[a] = -1, within.max[a] = 1;
    for (const double cell : {0.5, 0.05, 0.013}) {
      INFO(n << " points, cell " << cell);
      const std::vector<uint64_t> sorted = distinct_cell_keys(xyz.data(), n, box, cell, within, 0);
      const std::vector<uint64_t> bitmap = distinct_cell_keys(xyz.data(), n, box, cell, within, 1e9);
      Mesh points;
      points.positions = xyz;
      std::vector<uint32_t> list(n);
      for (size_t i = 0; i < n; ++i) list[i] = uint32_t(i);
      CHECK(sorted == sort_into_cells(points, list, box, cell).key);
      CHECK(bitmap == sorted);
    }
  }
}
