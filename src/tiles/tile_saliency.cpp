// tile_saliency(): the phases of saliency_tiles.h over a TileStore, see tile_saliency.h.
#include "tiles/tile_saliency.h"

#include "core/streamed_percentile.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <memory>

#include "core/stage_clock.h"
#include "tiles/background_write.h"
#include "tiles/tile_bytes.h"
#include "tiles/tile_file.h"
#include "tiles/tile_reduce.h"

namespace meshsal {

namespace {

void save_raw(const std::string& path, const TileRaw& r) {
  TileFileWriter out(path);
  out.put(r.global);
  out.put(r.positions);
  out.put(r.own);
  out.put(r.curvature);
  out.put(uint64_t(r.raw.size()));
  for (const auto& k : r.raw) out.put(k);
  out.put(r.pairs);
  out.close();
}

void shape_error() { throw Error("tiled saliency: a tile's file is out of shape"); }

TileRaw load_raw(const std::string& path, size_t scales) {
  TileFileReader in(path);
  TileRaw r;
  r.global = in.get_vector<uint32_t>();
  r.positions = in.get_vector<float>();
  r.own = in.get_vector<uint8_t>();
  r.curvature = in.get_vector<double>();
  if (in.get<uint64_t>() != scales) shape_error();
  r.raw.resize(scales);
  for (auto& k : r.raw) k = in.get_vector<double>();
  r.pairs = in.get<uint64_t>();
  const size_t n = r.global.size();
  if (r.own.size() != n || (!r.curvature.empty() && r.curvature.size() != n) ||
      (!r.positions.empty() && r.positions.size() != 3 * n))
    shape_error();
  for (const auto& k : r.raw)
    if (k.size() != n) shape_error();
  return r;
}

// Phase 1's candidates for local maxima, apart: phase 2 reads them alone (each field a
// vector of its own: no padding bytes in the file).
void save_candidates(const std::string& path, const std::vector<std::vector<MaxCandidate>>& c) {
  TileFileWriter out(path);
  out.put(uint64_t(c.size()));
  std::vector<uint32_t> vertex;
  std::vector<double> value, ring_max;
  for (const auto& k : c) {
    vertex.clear(), value.clear(), ring_max.clear();
    for (const MaxCandidate& m : k) vertex.push_back(m.vertex), value.push_back(m.value), ring_max.push_back(m.ring_max);
    out.put(vertex);
    out.put(value);
    out.put(ring_max);
  }
  out.close();
}

std::vector<std::vector<MaxCandidate>> load_candidates(const std::string& path, size_t scales) {
  TileFileReader in(path);
  if (in.get<uint64_t>() != scales) shape_error();
  std::vector<std::vector<MaxCandidate>> c(scales);
  for (auto& k : c) {
    const std::vector<uint32_t> vertex = in.get_vector<uint32_t>();
    const std::vector<double> value = in.get_vector<double>(), ring_max = in.get_vector<double>();
    if (value.size() != vertex.size() || ring_max.size() != vertex.size()) shape_error();
    for (size_t i = 0; i < vertex.size(); ++i) k.push_back({vertex[i], value[i], ring_max[i]});
  }
  return c;
}

// Phase C's outputs: a tile's points (read by every tile whose halo reaches it) and its
// query (read by itself).
//
// The points file holds the tile's points in zones, three bands per axis (within a halo's
// reach of the cube's low face, of its high face, and between), each zone ascending in
// whole-mesh order, after a header of each zone's count and box: a halo reaching a few
// percent of the diagonal into a neighbour half the box wide reads the bands facing it
// instead of all of the neighbour's points (igea_loop2 x4 in 8 tiles: every tile read
// every other tile's file whole).
constexpr uint64_t kZones = 27;
constexpr size_t kPointBytes = 4 + 12 + 8;  // number, position, curvature

struct Zone {
  uint64_t count = 0;
  BoundingBox box;
};

void save_points(const std::string& path, const TilePoints& p, const TilePlan& plan, size_t t) {
  const BoundingBox cube = tile_cube(plan, t);
  const double band = plan.source_margin + plan.query_margin;
  const size_t n = p.global.size();
  std::vector<uint8_t> zone(n);
  std::vector<Zone> zones(kZones);
  for (Zone& z : zones)
    for (int a = 0; a < 3; ++a) z.box.min[a] = INFINITY, z.box.max[a] = -INFINITY;
  for (size_t i = 0; i < n; ++i) {
    const float* x = &p.positions[3 * i];
    size_t z = 0;
    for (int a = 2; a >= 0; --a) z = 3 * z + (x[a] < cube.min[a] + band ? 0 : x[a] >= cube.max[a] - band ? 2 : 1);
    zone[i] = uint8_t(z);
    Zone& Z = zones[z];
    Z.count++;
    for (int a = 0; a < 3; ++a) Z.box.min[a] = std::min(Z.box.min[a], double(x[a])), Z.box.max[a] = std::max(Z.box.max[a], double(x[a]));
  }
  // The points zone by zone (a stable counting sort: each zone stays ascending).
  std::vector<size_t> at(kZones + 1, 0);
  for (size_t z = 0; z < kZones; ++z) at[z + 1] = at[z] + zones[z].count;
  std::vector<uint32_t> global(n);
  std::vector<float> positions(3 * n);
  std::vector<double> curvature(n);
  for (size_t i = 0; i < n; ++i) {
    const size_t j = at[zone[i]]++;
    global[j] = p.global[i];
    std::copy_n(&p.positions[3 * i], 3, &positions[3 * j]);
    curvature[j] = p.curvature[i];
  }
  TileFileWriter out(path);
  out.put(kZones);
  for (const Zone& z : zones) out.put(z.count), out.put(z.box);
  for (size_t z = 0, first = 0; z < kZones; first += zones[z].count, ++z) {
    const size_t m = zones[z].count;
    out.put_raw(global.data() + first, m);
    out.put_raw(positions.data() + 3 * first, 3 * m);
    out.put_raw(curvature.data() + first, m);
  }
  out.close();
}

bool meets(const BoundingBox& a, const BoundingBox& b) {
  for (int k = 0; k < 3; ++k)
    if (!(a.min[k] <= b.max[k] && a.max[k] >= b.min[k])) return false;
  return true;
}

// The zones of a tile's points file that meet `box` into p, one run each (`ends`).
void load_points(const std::string& path, const BoundingBox& box, TilePoints& p, std::vector<size_t>& ends) {
  TileFileReader in(path);
  if (in.get<uint64_t>() != kZones) shape_error();
  std::vector<Zone> zones(kZones);
  uint64_t total = 0;
  for (Zone& z : zones) {
    z.count = in.get<uint64_t>();
    z.box = in.get<BoundingBox>();
    if (z.count > in.left() / kPointBytes) shape_error();
    total += z.count;
  }
  if (total * kPointBytes != in.left()) shape_error();
  p.global.clear(), p.positions.clear(), p.curvature.clear();
  ends.clear();
  for (const Zone& z : zones) {
    if (z.count == 0) continue;
    if (!meets(z.box, box)) {
      in.skip(z.count * kPointBytes);
      continue;
    }
    const size_t at = p.global.size(), m = size_t(z.count);
    p.global.resize(at + m), p.positions.resize(3 * (at + m)), p.curvature.resize(at + m);
    in.get_raw(&p.global[at], m);
    in.get_raw(&p.positions[3 * at], 3 * m);
    in.get_raw(&p.curvature[at], m);
    ends.push_back(at + m);
  }
}

void save_query(const std::string& path, const TileQuery& q) {
  TileFileWriter out(path);
  out.put(uint8_t(q.empty ? 1 : 0));
  out.put(q.query_box);
  out.put(q.corners);
  out.put(q.own);
  out.put(q.triangles);
  out.close();
}

TileQuery load_query(const std::string& path) {
  TileFileReader in(path);
  TileQuery q;
  q.empty = in.get<uint8_t>() != 0;
  q.query_box = in.get<BoundingBox>();
  q.corners = in.get_vector<uint32_t>();
  q.own = in.get_vector<uint8_t>();
  q.triangles = in.get_vector<uint32_t>();
  if (q.own.size() != q.corners.size() || q.triangles.size() % 3 != 0)
    shape_error();
  for (uint32_t c : q.triangles)
    if (c >= q.corners.size()) shape_error();
  return q;
}

// The values of a results record: S and Sm, with the scales also the curvature and raw
// maps (the first of TileResultReader's values, in their order).
size_t record_values(size_t scales, bool kept) { return kept ? kResultWidth + scales : 2; }

// What each tile's results file holds: a record per own point in vertex order, its number
// then its record_values.
void save_result(const std::string& path, const TileResult& r, bool kept) {
  ScratchWriter out(path);
  const size_t scales = r.raw.size(), width = record_values(scales, kept), rec = 4 + 8 * width;
  constexpr size_t kRecords = 4096;  // per write
  std::vector<uint8_t> buf(kRecords * rec);
  std::vector<double> v(kResultWidth + scales);
  for (size_t first = 0; first < r.global.size(); first += kRecords) {
    const size_t count = std::min(kRecords, r.global.size() - first);
    for (size_t i = first; i < first + count; ++i) {
      v[0] = r.saliency[i];
      v[1] = r.smoothed.empty() ? 0.0 : r.smoothed[i];
      v[2] = r.curvature.empty() ? 0.0 : r.curvature[i];  // (kept only with the scales)
      for (size_t k = 0; k < scales; ++k) v[3 + k] = r.raw[k][i];
      uint8_t* at = &buf[(i - first) * rec];
      std::memcpy(at, &r.global[i], 4);
      std::memcpy(at + 4, v.data(), 8 * width);
    }
    out.write(buf.data(), count * rec);
  }
  out.close();
}

}  // namespace

std::string tile_result_file(const TileStore& store, size_t t) {
  return store.dir.file("result_" + std::to_string(t) + ".bin");
}

void tile_saliency(const TileStore& store, const SaliencyOptions& options, OutOfCoreReport& report, bool scales) {
  TileExchange* exchange = options.exchange;
  const int rank = exchange ? exchange->rank() : 0, ranks = exchange ? exchange->ranks() : 1;
  StageClock clock(report.stages);
  auto progress = [&](const char* stage, double f) {
    if (options.progress) options.progress(stage, f);
  };
  TilePlan plan = store.plan;
  const size_t ntiles = tile_count(plan);
  report.vertices = store.vertices;
  report.points = store.points;
  report.triangles = store.triangles;
  report.tiles = ntiles;
  report.eps = plan.eps;
  report.tile_estimate = store.largest_tile_estimate;
  std::vector<size_t> mine;
  for (size_t t = size_t(rank); t < ntiles; t += size_t(ranks)) mine.push_back(t);
  auto raw_file = [&](size_t t) { return store.dir.file("raw_" + std::to_string(t) + ".bin"); };
  auto candidates_file = [&](size_t t) { return store.dir.file("candidates_" + std::to_string(t) + ".bin"); };

  // Phase C: each tile's own points and their curvature, kept for the tiles whose halos
  // reach them (any rank's: the folder is shared) and the tile's query for itself.
  auto points_file = [&](size_t t) { return store.dir.file("points_" + std::to_string(t) + ".bin"); };
  auto query_file = [&](size_t t) { return store.dir.file("query_" + std::to_string(t) + ".bin"); };
  // The fast method's phase 0 from the same points: the occupied cells inside each tile,
  // and those across its faces (on the writes' thread).
  const bool fast = plan.method == Method::Fast;
  TileCells cells = fast ? tile_cells(plan, 0, TilePoints{}) : TileCells{};
  {
    const TileSource source = store_tile_source(store);
    BackgroundWrite writes;  // a tile's files written while the next one is computed
    for (size_t i = 0; i < mine.size(); ++i) {
      progress("curvature", double(i) / mine.size());
      const size_t t = mine[i];
      auto c = std::make_shared<TileCurvature>(tile_curvature(plan, t, source));
      // (Its cells counted beside the writes, one tile at a time: the counts are added in
      // tile order.)
      writes.submit([&, c, t] {
        if (fast) add_tile_cells(cells, tile_cells(plan, t, c->points));
        save_points(points_file(t), c->points, plan, t);  // empty too: a missing file is an error
        save_query(query_file(t), c->query);
      });
    }
    writes.finish();
  }
  tile_gather(exchange, {});  // every rank's points on disk before any tile reads them
  const TilePointSource point_source = [&](size_t t, const BoundingBox& box, TilePoints& scratch,
                                           std::vector<size_t>& ends) -> const TilePoints& {
    load_points(points_file(t), box, scratch, ends);
    return scratch;
  };
  clock.lap("curvature");

  // Phase 0 (fast): the whole mesh's occupied cells, over every process's tiles.
  if (fast) {
    plan.fast_cells = whole_mesh_cells(exchange, cells);
    cells = TileCells{};
    clock.lap("cell counts");
  }

  // Phase 1: raw maps, each tile's kept on disk; the scales' maxima over all tiles.
  std::vector<ScaleMax> max(options.scales.size());
  uint64_t pairs = 0;
  {
    BackgroundWrite writes;
    for (size_t i = 0; i < mine.size(); ++i) {
      progress("tiles", double(i) / mine.size());
      const size_t t = mine[i];
      auto raw = std::make_shared<TileRaw>(tile_raw_maps(plan, t, load_query(query_file(t)), point_source));
      std::remove(query_file(t).c_str());
      pairs += raw->pairs;
      merge_scale_max(max, tile_scale_max(*raw));
      if (!scales) std::vector<double>().swap(raw->curvature);  // the results keep it only with the scales
      writes.submit([&, raw, t] {
        save_raw(raw_file(t), *raw);
        save_candidates(candidates_file(t), raw->candidates);
      });
    }
    writes.finish();
  }
  progress("tiles", 1.0);
  reduce_scale_max(exchange, max, pairs);
  report.pairs = pairs;
  // The reduction above has every rank past phase 1: the points can go.
  for (size_t t : mine) std::remove(points_file(t).c_str());
  clock.lap("tile raw maps");

  // Phase 2: mbar from the local maxima of every tile, in vertex order.
  std::vector<std::vector<LocalMax>> maxima(options.scales.size());
  for (size_t t : mine) {
    const auto m = tile_local_maxima(load_candidates(candidates_file(t), options.scales.size()), max);
    std::remove(candidates_file(t).c_str());
    for (size_t k = 0; k < m.size(); ++k) maxima[k].insert(maxima[k].end(), m[k].begin(), m[k].end());
  }
  const std::vector<double> mbar = reduce_mbar(exchange, std::move(maxima), max);
  clock.lap("suppression");

  // Phase 3: each tile's results to disk; the saliency's range for the colours; S of the
  // own points to a file per rank, for its percentiles.
  double lo = INFINITY, hi = -INFINITY, sum = 0;
  auto s_file = [&](int r) { return store.dir.file("s_rank" + std::to_string(r) + ".f64"); };
  ScratchWriter s_out(s_file(rank));
  {
    BackgroundWrite writes;
    for (size_t i = 0; i < mine.size(); ++i) {
      progress(plan.smoothed ? "smoothing" : "saliency", double(i) / mine.size());
      const size_t t = mine[i];
      const std::string raw_path = raw_file(t);
      auto r = std::make_shared<TileResult>(tile_finish(load_raw(raw_path, options.scales.size()), plan, max, mbar));
      std::remove(raw_path.c_str());
      for (double s : r->saliency) lo = std::min(lo, s), hi = std::max(hi, s), sum += s;
      writes.submit([&, r, t] {
        s_out.write_vector(r->saliency);
        save_result(tile_result_file(store, t), *r, scales);
      });
    }
    writes.finish();
  }
  s_out.close();
  {
    TileBytes b;
    b.put(lo);
    b.put(hi);
    b.put(sum);
    sum = 0;
    for (const auto& bytes : tile_gather(exchange, b.data)) {
      TileBytesReader in{bytes};
      lo = std::min(lo, in.get<double>());
      hi = std::max(hi, in.get<double>());
      sum += in.get<double>();
    }
  }
  report.saliency_min = lo;
  report.saliency_max = hi;
  report.saliency_mean = store.points ? sum / double(store.points) : 0;
  // The percentiles saliency_stats gives (nearest rank), streamed from every rank's file by
  // rank 0, which reports (the gather above: the files are complete).
  if (store.points > 0) lead_step(exchange, [&] {
    const ValueStream all = [&](const std::function<void(double)>& take) {
      std::vector<double> buf(1 << 16);
      for (int r = 0; r < ranks; ++r) {
        ScratchReader in(s_file(r));
        for (size_t got; (got = in.read(buf.data(), buf.size() * 8) / 8) > 0;)
          for (size_t i = 0; i < got; ++i) take(buf[i]);
      }
    };
    auto rank_of = [&](double p) {
      const uint64_t k = uint64_t(std::ceil(p / 100.0 * double(store.points)));
      return std::min(store.points - 1, k == 0 ? 0 : k - 1);
    };
    const std::vector<double> at = streamed_kths(all, {rank_of(10), rank_of(50), rank_of(90), rank_of(99)});
    report.saliency_p10 = at[0];
    report.saliency_p50 = at[1];
    report.saliency_p90 = at[2];
    report.saliency_p99 = at[3];
  });
  tile_gather(exchange, {});  // rank 0 has read every file (also where no point was)
  std::remove(s_file(rank).c_str());
  clock.lap("saliency");

}

TileResultReader::TileResultReader(const TileStore& store, size_t scales, bool kept)
    : store_(store), scales_(scales), kept_(kept), offset_(tile_count(store.plan), 0),
      ahead_(tile_count(store.plan), 0) {}

void TileResultReader::read(uint64_t first, size_t count, std::vector<double>& values, std::vector<uint8_t>& point) {
  if (first < next_) throw Error("internal: tile results read out of order");
  next_ = first + count;
  const size_t width = kResultWidth + scales_, stored = record_values(scales_, kept_), rec = 4 + 8 * stored;
  values.assign(count * width, 0.0);
  point.assign(count, 0);
  constexpr size_t kRecords = 4096;  // per read
  std::vector<uint8_t> buf(kRecords * rec);
  for (size_t t = 0; t < offset_.size(); ++t) {
    if (ahead_[t] >= first + count) continue;  // its next record is beyond this block (or none is left)
    ScratchReader in(tile_result_file(store_, t));  // every tile writes one, empty or not
    in.seek(offset_[t]);
    for (bool more = true; more;) {
      const size_t bytes = in.read(buf.data(), buf.size());
      if (bytes % rec != 0) throw Error("tiled saliency: a tile's results file is out of shape");
      const size_t got = bytes / rec;
      more = got == kRecords;
      if (got < kRecords) ahead_[t] = UINT64_MAX;  // the file ends in this read
      for (size_t i = 0; i < got; ++i) {
        const uint8_t* r = &buf[i * rec];
        uint32_t v;
        std::memcpy(&v, r, 4);
        if (v >= first + count) {
          ahead_[t] = v;  // left for a later block
          more = false;
          break;
        }
        offset_[t] += rec;
        if (v < first) continue;  // a vertex of a block skipped
        point[v - first] = 1;
        std::memcpy(&values[(v - first) * width], r + 4, 8 * stored);
      }
    }
  }
}

}  // namespace meshsal
