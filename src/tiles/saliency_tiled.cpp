// compute_saliency_tiled(): the phases of saliency_tiles.h over a mesh in memory, this
// process's share of the tiles, the reductions through a TileExchange when one is given.
#include "core/parallel.h"
#include "core/stage_clock.h"
#include "tiles/saliency_tiles.h"
#include "tiles/tile_bytes.h"
#include "tiles/tile_reduce.h"

namespace meshsal {

SaliencyResult compute_saliency_tiled(const Mesh& mesh, const SaliencyOptions& opt) {
  if (opt.method != Method::Exact && opt.method != Method::Fast)
    throw Error("internal: method auto not resolved");
  TileExchange* exchange = opt.exchange;
  const int rank = exchange ? exchange->rank() : 0, ranks = exchange ? exchange->ranks() : 1;
  if (ranks < 1 || rank < 0 || rank >= ranks) throw Error("tiled saliency: the exchange's rank is out of range");
  SaliencyResult r;
  r.method = opt.method;
  r.backend_name = "cpu (" + std::to_string(resolve_threads(opt.threads)) + " threads)";
  r.ranks = ranks;
  StageClock clock(r.stages);

  r.is_point = referenced_vertices(mesh);
  const size_t n = mesh.vertex_count();
  uint64_t points = 0;
  for (uint8_t f : r.is_point) points += f;
  const BoundingBox box = mesh_points_bbox(mesh, r.is_point);
  TilePlan plan = make_tile_plan(box, points, opt, opt.tiles);
  r.eps = plan.eps;
  r.tiles = tile_count(plan);
  const TileBuckets buckets = bucket_triangles(mesh, plan);
  const TileSource source = memory_tile_source(mesh, buckets);
  std::vector<size_t> mine;
  for (size_t t = size_t(rank); t < r.tiles; t += size_t(ranks)) mine.push_back(t);
  auto report = [&](const char* stage, double f) {
    if (opt.progress) opt.progress(stage, f);
  };

  // Phase C: each tile's own points and their curvature; every process holds every tile's
  // (the halos reach into other processes' tiles).
  std::vector<TilePoints> tile_points(r.tiles);
  std::vector<TileQuery> queries;
  for (size_t i = 0; i < mine.size(); ++i) {
    report("curvature", double(i) / mine.size());
    TileCurvature c = tile_curvature(plan, mine[i], source);
    tile_points[mine[i]] = std::move(c.points);
    queries.push_back(std::move(c.query));
  }
  if (ranks > 1) {
    TileBytes b;
    for (size_t t : mine) {
      b.put(uint64_t(t));
      b.put(tile_points[t].global);
      b.put(tile_points[t].positions);
      b.put(tile_points[t].curvature);
    }
    for (const auto& bytes : tile_gather(exchange, b.data)) {
      TileBytesReader in{bytes};
      while (!in.done()) {
        const uint64_t t = in.get<uint64_t>();
        if (t >= r.tiles) throw Error("tiled saliency: a process sent a tile out of range");
        TilePoints& p = tile_points[t];
        p.global = in.get_vector<uint32_t>();
        p.positions = in.get_vector<float>();
        p.curvature = in.get_vector<double>();
        if (p.positions.size() != 3 * p.global.size() || p.curvature.size() != p.global.size())
          throw Error("tiled saliency: a process sent a tile's points out of shape");
      }
    }
  }
  const TilePointSource point_source = memory_point_source(tile_points);
  clock.lap("curvature");

  // Phase 0 (fast): the whole mesh's occupied cells, summed over every tile.
  if (plan.method == Method::Fast) {
    TileCells cells = tile_cells(plan, 0, TilePoints{});  // (zero counts: a process may have no tile)
    for (size_t t : mine) add_tile_cells(cells, tile_cells(plan, t, tile_points[t]));
    plan.fast_cells = whole_mesh_cells(exchange, cells);
    clock.lap("cell counts");
  }

  // Phase 1: raw maps per tile; each scale's maximum over all tiles.
  std::vector<TileRaw> raws;
  std::vector<ScaleMax> max(opt.scales.size());
  for (size_t i = 0; i < mine.size(); ++i) {
    report("tiles", double(i) / mine.size());
    raws.push_back(tile_raw_maps(plan, mine[i], queries[i], point_source));
    queries[i] = TileQuery{};  // its triangles and corners are done with
    r.pairs += raws.back().pairs;
    merge_scale_max(max, tile_scale_max(raws.back()));
  }
  report("tiles", 1.0);
  std::vector<TilePoints>().swap(tile_points);
  reduce_scale_max(exchange, max, r.pairs);
  clock.lap("tile raw maps");

  // Phase 2: mbar from every tile's local maxima, in vertex order.
  std::vector<std::vector<LocalMax>> maxima(opt.scales.size());
  for (TileRaw& raw : raws) {
    std::vector<std::vector<LocalMax>> m = tile_local_maxima(raw.candidates, max);
    std::vector<std::vector<MaxCandidate>>().swap(raw.candidates);
    for (size_t k = 0; k < m.size(); ++k) maxima[k].insert(maxima[k].end(), m[k].begin(), m[k].end());
  }
  const std::vector<double> mbar = reduce_mbar(exchange, std::move(maxima), max);
  clock.lap("suppression");

  // Phase 3: each tile's own results, shared so that every process holds the whole map.
  TileBytes results;
  for (TileRaw& raw : raws) {
    const TileResult t = tile_finish(raw, plan, max, mbar);
    results.put(t.global);
    results.put(t.curvature);
    results.put(t.saliency);
    results.put(t.smoothed);
    for (const auto& k : t.raw) results.put(k);
  }
  std::vector<TileRaw>().swap(raws);
  r.curvature.assign(n, 0.0);
  r.saliency.assign(n, 0.0);
  if (opt.smoothed) r.smoothed.assign(n, 0.0);
  r.raw.assign(opt.scales.size(), std::vector<double>(n, 0.0));
  for (const auto& bytes : tile_gather(exchange, results.data)) {
    TileBytesReader in{bytes};
    while (in.at < bytes.size()) {
      const std::vector<uint32_t> global = in.get_vector<uint32_t>();
      const std::vector<double> curvature = in.get_vector<double>(), saliency = in.get_vector<double>(),
                                smoothed = in.get_vector<double>();
      std::vector<std::vector<double>> raw;
      for (size_t k = 0; k < opt.scales.size(); ++k) raw.push_back(in.get_vector<double>());
      for (size_t i = 0; i < global.size(); ++i) {
        const uint32_t v = global[i];
        if (v >= n) throw Error("tiled saliency: a process sent a vertex out of range");
        r.curvature[v] = curvature[i];
        r.saliency[v] = saliency[i];
        if (opt.smoothed) r.smoothed[v] = smoothed.at(i);
        for (size_t k = 0; k < raw.size(); ++k) r.raw[k][v] = raw[k][i];
      }
    }
  }
  clock.lap(opt.smoothed ? "saliency and smoothing" : "saliency");
  return r;
}

}  // namespace meshsal
