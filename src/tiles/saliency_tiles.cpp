// The phases of a tiled saliency run (saliency_tiles.h), each on one tile.
#include "tiles/saliency_tiles.h"

#include <algorithm>
#include <cmath>

#include "core/adjacency.h"
#include "core/parallel.h"
#include "core/radix_sort.h"
#include "saliency/curvature.h"
#include "saliency/gaussian_filter.h"
#include "saliency/gaussian_filter_fast.h"
#include "saliency/saliency.h"
#include "saliency/sparse_cells.h"

namespace meshsal {

namespace {

GridFrame frame_of(const TilePlan& plan) { return GridFrame{plan.box, plan.points}; }

std::vector<double> filter_sigmas(const TilePlan& plan) {
  std::vector<double> sigmas;
  for (double u : filter_sigma_units(plan.scales)) sigmas.push_back(u * plan.eps);
  return sigmas;
}

// How far beyond a query point the filter of these sigmas reads: the cutoff 2 s plus whole
// cells, so that every cell a sweep visits is held complete (two cells: the exact sweep's
// grid rows end on cell boundaries; the fast method queries at a cell's centroid and reads
// cells whose centroid is within 2 s, each up to a cell wide).
double reach(const TilePlan& plan, const std::vector<double>& sigmas) {
  if (plan.method == Method::Exact)
    return 2 * *std::max_element(sigmas.begin(), sigmas.end()) + 2 * sweep_grid_cell(sigmas, frame_of(plan));
  double r = 0;
  for (double s : sigmas) r = std::max(r, 2 * s + 3 * fast_cell_edge(plan.box, s));
  return r;
}

bool in_box(const float* p, const BoundingBox& b, double margin) {
  for (int a = 0; a < 3; ++a)
    if (!(double(p[a]) >= b.min[a] - margin && double(p[a]) <= b.max[a] + margin)) return false;
  return true;
}

void grow(BoundingBox& b, const float* p) {
  for (int a = 0; a < 3; ++a) {
    b.min[a] = std::min(b.min[a], double(p[a]));
    b.max[a] = std::max(b.max[a], double(p[a]));
  }
}

BoundingBox empty_box() {
  BoundingBox b;
  for (int a = 0; a < 3; ++a) b.min[a] = INFINITY, b.max[a] = -INFINITY;
  return b;
}

}  // namespace

TilePlan make_tile_plan(const BoundingBox& box, uint64_t points, const SaliencyOptions& options,
                        unsigned tiles) {
  TilePlan plan;
  plan.method = options.method;
  if (plan.method != Method::Exact && plan.method != Method::Fast)
    throw Error("internal: a tile plan needs the method decided");
  plan.scales = options.scales;
  plan.smoothed = options.smoothed;
  plan.threads = options.threads;
  plan.box = box;
  plan.points = points;
  plan.eps = options.eps_frac * box.diagonal();
  double longest = 0;
  for (int a = 0; a < 3; ++a) longest = std::max(longest, box.max[a] - box.min[a]);
  tiles = std::max(1u, tiles);
  plan.tile_edge = longest > 0 ? longest / tiles : 1.0;
  for (int a = 0; a < 3; ++a)
    plan.tiles[a] = std::max(1, int(std::ceil((box.max[a] - box.min[a]) / plan.tile_edge)));
  plan.source_margin = reach(plan, filter_sigmas(plan));
  plan.query_margin = plan.smoothed ? reach(plan, {3 * plan.eps}) : 0.0;
  return plan;
}

size_t tile_count(const TilePlan& plan) {
  return size_t(plan.tiles[0]) * plan.tiles[1] * plan.tiles[2];
}

BoundingBox tile_cube(const TilePlan& plan, size_t t) {
  const size_t col[3] = {t % size_t(plan.tiles[0]), t / size_t(plan.tiles[0]) % size_t(plan.tiles[1]),
                         t / (size_t(plan.tiles[0]) * size_t(plan.tiles[1]))};
  BoundingBox cube;
  for (int a = 0; a < 3; ++a) {
    cube.min[a] = plan.box.min[a] + double(col[a]) * plan.tile_edge;
    cube.max[a] = col[a] + 1 == size_t(plan.tiles[a]) ? plan.box.max[a] : cube.min[a] + plan.tile_edge;
  }
  return cube;
}

std::vector<double> tile_cell_sigmas(const TilePlan& plan) {
  std::vector<double> sigmas = filter_sigmas(plan);
  sigmas.push_back(3 * plan.eps);
  return sigmas;
}

namespace {

// Each triangle once, in the mesh's order (a tile's buckets overlap where a triangle has
// corners in two tiles).
void distinct_faces(std::vector<TileFace>& faces) {
  // A bucket filled in one block of vertices is in face order already, each face once; a
  // few blocks or ranks give a few runs in face order (a face with corners in two blocks in
  // two of them), merged pairwise; many, a radix sort.
  std::vector<size_t> run{0};
  for (size_t i = 1; i < faces.size(); ++i)
    if (faces[i - 1].face >= faces[i].face) run.push_back(i);
  if (run.size() == 1) return;
  auto by_face = [](const TileFace& a, const TileFace& b) { return a.face < b.face; };
  if (run.size() <= 64) {
    run.push_back(faces.size());
    std::vector<TileFace> merged(faces.size());
    while (run.size() > 2) {
      std::vector<size_t> next{0};
      for (size_t r = 0; r + 1 < run.size(); r += 2) {
        const size_t b = run[r], m = run[r + 1], e = r + 2 < run.size() ? run[r + 2] : m;
        std::merge(faces.begin() + long(b), faces.begin() + long(m), faces.begin() + long(m), faces.begin() + long(e),
                   merged.begin() + long(b), by_face);
        next.push_back(e);
      }
      faces.swap(merged);
      run.swap(next);
    }
    faces.erase(std::unique(faces.begin(), faces.end(), [](const TileFace& a, const TileFace& b) { return a.face == b.face; }),
                faces.end());
    return;
  }
  // 32-bit keys: face numbers fit, and each radix pass moves half the bytes of 64-bit ones.
  std::vector<uint32_t> key(faces.size());
  std::vector<uint32_t> index(faces.size());
  uint32_t largest = 0;
  for (size_t i = 0; i < faces.size(); ++i) {
    key[i] = faces[i].face;
    index[i] = uint32_t(i);
    largest = std::max(largest, faces[i].face);
  }
  radix_sort(key, index, largest);
  std::vector<TileFace> out;
  out.reserve(faces.size());
  for (size_t i = 0; i < index.size(); ++i)
    if (i == 0 || key[i] != key[i - 1]) out.push_back(faces[index[i]]);
  faces.swap(out);
}

// The distinct corners of `faces` in vertex order, each corner's number among them
// (local[3 f + k]) and their positions.
struct Corners {
  std::vector<uint32_t> ids, local;
  std::vector<float> pos;
};

void corners_of(const std::vector<TileFace>& faces, const TileSource& source, Corners& c) {
  const size_t n = 3 * faces.size();
  std::vector<uint32_t> key(n);  // vertex numbers fit in 32 bits (see distinct_faces)
  std::vector<uint32_t> slot(n);
  uint32_t largest = 0;
  for (size_t f = 0; f < faces.size(); ++f)
    for (int k = 0; k < 3; ++k) {
      key[3 * f + k] = faces[f].c[k];
      slot[3 * f + k] = uint32_t(3 * f + k);
      largest = std::max(largest, faces[f].c[k]);
    }
  radix_sort(key, slot, largest);
  c.ids.clear();
  c.local.assign(n, 0);
  for (size_t i = 0; i < n; ++i) {
    if (i == 0 || key[i] != key[i - 1]) c.ids.push_back(key[i]);
    c.local[slot[i]] = uint32_t(c.ids.size() - 1);
  }
  source.positions(c.ids, c.pos);
}

}  // namespace

TileCurvature tile_curvature(const TilePlan& plan, size_t t, const TileSource& source) {
  // The tile's bucket: its own points and their 1-rings (every corner of those triangles).
  TileCurvature out;
  std::vector<TileFace> faces;
  source.bucket(t, faces);
  distinct_faces(faces);
  Corners c;
  corners_of(faces, source, c);
  std::vector<TileFace>().swap(faces);
  const size_t n = c.ids.size();
  std::vector<uint8_t> own(n, 0);
  BoundingBox own_box = empty_box(), query_box = empty_box();
  for (size_t i = 0; i < n; ++i) {
    grow(query_box, &c.pos[3 * i]);
    if (tile_of(plan, &c.pos[3 * i]) == t) own[i] = 1, grow(own_box, &c.pos[3 * i]);
  }
  if (own_box.empty()) return out;
  for (int a = 0; a < 3; ++a) {
    query_box.min[a] = std::min(query_box.min[a], own_box.min[a] - plan.query_margin);
    query_box.max[a] = std::max(query_box.max[a], own_box.max[a] + plan.query_margin);
  }
  out.query.empty = false;
  out.query.query_box = query_box;
  // The sub-mesh of the bucket: its triangles in the mesh's order, their corners in vertex
  // order. Each method's curvature as the whole mesh computes it (saliency_cpu.cpp,
  // saliency_fast_cpu.cpp): an own point has all its triangles here, so the same bits.
  Mesh sub;
  sub.positions = std::move(c.pos);
  sub.triangles = std::move(c.local);
  std::vector<double> H;
  if (plan.method == Method::Fast) {
    H = mean_curvature_morton(sub, plan.box, plan.threads);
  } else {
    const Adjacency adj = build_adjacency(sub, plan.threads);
    H = mean_curvature(sub, adj, vertex_normals(sub, plan.threads), plan.threads);
  }
  TilePoints& p = out.points;
  for (size_t i = 0; i < n; ++i) {
    if (!own[i]) continue;
    p.global.push_back(c.ids[i]);
    p.positions.insert(p.positions.end(), &sub.positions[3 * i], &sub.positions[3 * i + 3]);
    p.curvature.push_back(H[i]);
  }
  out.query.corners = std::move(c.ids);
  out.query.own = std::move(own);
  out.query.triangles = std::move(sub.triangles);
  return out;
}

TilePointSource memory_point_source(const std::vector<TilePoints>& points) {
  return [&points](size_t t, const BoundingBox&, TilePoints&, std::vector<size_t>& ends) -> const TilePoints& {
    ends.assign(1, points[t].global.size());
    return points[t];
  };
}

TilePoints gather_points(const TilePlan& plan, const BoundingBox& box, const TilePointSource& source) {
  size_t lo[3], hi[3];
  for (int a = 0; a < 3; ++a) lo[a] = tile_column(plan, box.min[a], a), hi[a] = tile_column(plan, box.max[a], a);
  // Each run of a tile's points is ascending and the tiles disjoint: a merge of the runs
  // puts the union in whole-mesh order.
  TilePoints all, scratch;
  std::vector<size_t> run{0};  // the runs' starts in `all`
  std::vector<size_t> ends;
  for (size_t z = lo[2]; z <= hi[2]; ++z)
    for (size_t y = lo[1]; y <= hi[1]; ++y)
      for (size_t x = lo[0]; x <= hi[0]; ++x) {
        const TilePoints& p = source((z * size_t(plan.tiles[1]) + y) * size_t(plan.tiles[0]) + x, box, scratch, ends);
        for (size_t r = 0, i = 0; r < ends.size(); ++r) {
          for (; i < ends[r]; ++i) {
            if (!in_box(&p.positions[3 * i], box, 0.0)) continue;
            all.global.push_back(p.global[i]);
            all.positions.insert(all.positions.end(), &p.positions[3 * i], &p.positions[3 * i + 3]);
            all.curvature.push_back(p.curvature[i]);
          }
          if (all.global.size() > run.back()) run.push_back(all.global.size());
        }
      }
  if (run.size() <= 2) return all;  // one run (or none): in order already
  // The runs merged by a radix sort of the numbers (linear, on the threads; a heap of the
  // runs took half of the gathering with a tile's bands as runs).
  const size_t n = all.global.size();
  std::vector<uint32_t> key = all.global, from(n);
  uint32_t largest = 0;
  for (size_t i = 0; i < n; ++i) from[i] = uint32_t(i), largest = std::max(largest, key[i]);
  radix_sort(key, from, largest, plan.threads);
  TilePoints out;
  out.global = std::move(key);
  out.positions.resize(3 * n);
  out.curvature.resize(n);
  parallel_for(n, plan.threads, 1 << 16, [&](size_t begin, size_t end) {
    for (size_t i = begin; i < end; ++i) {
      std::copy_n(&all.positions[3 * size_t(from[i])], 3, &out.positions[3 * i]);
      out.curvature[i] = all.curvature[from[i]];
    }
  });
  return out;
}

TileBuckets bucket_triangles(const Mesh& mesh, const TilePlan& plan) {
  TileBuckets b;
  const size_t nt = mesh.triangle_count();
  b.start.assign(tile_count(plan) + 2, 0);
  // The distinct tiles of a triangle's corners, counted then filled (a counting sort).
  auto tiles_of = [&](size_t f, size_t out[3]) {
    int n = 0;
    for (int k = 0; k < 3; ++k) {
      const size_t t = tile_of(plan, &mesh.positions[3 * size_t(mesh.triangles[3 * f + k])]);
      if (std::find(out, out + n, t) == out + n) out[n++] = t;
    }
    return n;
  };
  size_t ts[3];
  for (size_t f = 0; f < nt; ++f)
    for (int i = 0, n = tiles_of(f, ts); i < n; ++i) b.start[ts[i] + 2]++;
  for (size_t t = 2; t < b.start.size(); ++t) b.start[t] += b.start[t - 1];
  b.faces.resize(b.start.back());
  for (size_t f = 0; f < nt; ++f)
    for (int i = 0, n = tiles_of(f, ts); i < n; ++i) b.faces[b.start[ts[i] + 1]++] = uint32_t(f);
  b.start.pop_back();
  return b;
}

TileSource memory_tile_source(const Mesh& mesh, const TileBuckets& buckets) {
  TileSource s;
  s.bucket = [&mesh, &buckets](size_t t, std::vector<TileFace>& into) {
    for (uint64_t i = buckets.start[t]; i < buckets.start[t + 1]; ++i) {
      const uint32_t f = buckets.faces[i];
      const uint32_t* c = &mesh.triangles[3 * size_t(f)];
      into.push_back({f, {c[0], c[1], c[2]}});
    }
  };
  s.positions = [&mesh](const std::vector<uint32_t>& sorted, std::vector<float>& xyz) {
    xyz.resize(3 * sorted.size());
    for (size_t i = 0; i < sorted.size(); ++i)
      std::copy(&mesh.positions[3 * size_t(sorted[i])], &mesh.positions[3 * size_t(sorted[i])] + 3, &xyz[3 * i]);
  };
  return s;
}

TileCells tile_cells(const TilePlan& plan, size_t t, const TilePoints& own) {
  const std::vector<double> sigmas = tile_cell_sigmas(plan);
  TileCells c;
  c.inner.assign(sigmas.size(), 0);
  c.across.resize(sigmas.size());
  const size_t n = own.global.size();
  if (n == 0) return c;
  const BoundingBox cube = tile_cube(plan, t);  // (its points lie in it, up to rounding)
  for (size_t k = 0; k < sigmas.size(); ++k) {
    const double cell = fast_cell_edge(plan.box, sigmas[k]);
    uint64_t dims[3];
    cell_dims(plan.box, cell, dims);
    // A cell within one tile column on every axis holds points of one tile alone: this
    // one's. One that reaches across a face (its box widened by far more than a point's
    // key can round: a cell called shared when it is not costs nothing) may hold a
    // neighbour's too.
    const double slack = 1e-3 * cell;
    for (uint64_t key : distinct_cell_keys(own.positions.data(), n, plan.box, cell, cube, 16, plan.threads)) {
      const uint64_t at[3] = {key % dims[0], key / dims[0] % dims[1], key / (dims[0] * dims[1])};
      bool across = false;
      for (int a = 0; a < 3 && !across; ++a) {
        const double lo = plan.box.min[a] + double(at[a]) * cell;
        across = tile_column(plan, lo - slack, a) != tile_column(plan, lo + cell + slack, a);
      }
      if (across) c.across[k].push_back(key);
      else c.inner[k]++;
    }
  }
  return c;
}

void add_tile_cells(TileCells& into, const TileCells& tile) {
  if (into.inner.empty()) into.inner.assign(tile.inner.size(), 0), into.across.resize(tile.across.size());
  for (size_t k = 0; k < tile.inner.size(); ++k) {
    into.inner[k] += tile.inner[k];
    into.across[k].insert(into.across[k].end(), tile.across[k].begin(), tile.across[k].end());
  }
}

TileRaw tile_raw_maps(const TilePlan& plan, size_t t, const TileQuery& query, const TilePointSource& source) {
  TileRaw r;
  const size_t scales = plan.scales.size();
  r.raw.resize(scales);
  r.candidates.resize(scales);
  if (query.empty) return r;
  // The source points: every mesh point within the filter's reach of a query point.
  BoundingBox source_box = query.query_box;
  for (int a = 0; a < 3; ++a) source_box.min[a] -= plan.source_margin, source_box.max[a] += plan.source_margin;
  TilePoints src = gather_points(plan, source_box, source);
  Mesh points;
  points.positions = std::move(src.positions);
  const size_t n = src.global.size();
  // The query points, in whole-mesh order: qi[v] their numbers among them.
  std::vector<uint8_t> is_query(n);
  std::vector<uint32_t> qi(n, UINT32_MAX);
  uint32_t queries = 0;
  for (size_t v = 0; v < n; ++v)
    if (in_box(&points.positions[3 * v], query.query_box, 0.0)) is_query[v] = 1, qi[v] = queries++;
  // The bucket's corners among them (both ascending: one walk); every corner is a query
  // point (the query box holds them).
  std::vector<uint32_t> corner(query.corners.size());
  for (size_t i = 0, v = 0; i < corner.size(); ++i) {
    while (v < n && src.global[v] < query.corners[i]) ++v;
    if (v == n || src.global[v] != query.corners[i] || qi[v] == UINT32_MAX)
      throw Error("internal: a tile's halo misses a 1-ring neighbour");
    corner[i] = qi[v];
  }
  // The same averages as compute_saliency_cpu, on the source points.
  const std::vector<double> units = filter_sigma_units(plan.scales);
  const std::vector<double> sigmas = filter_sigmas(plan);
  FilterScope scope;
  scope.frame = frame_of(plan);
  scope.query = &is_query;
  // G[k]: sigma k's averages at the query points (in query numbers).
  std::vector<std::vector<double>> G(sigmas.size());
  auto keep_queries = [&](const std::vector<double>& at_points, std::vector<double>& into) {
    into.resize(queries);
    parallel_for(n, plan.threads, 1 << 16, [&](size_t begin, size_t end) {  // each query its own slot
      for (size_t v = begin; v < end; ++v)
        if (qi[v] != UINT32_MAX) into[qi[v]] = at_points[v];
    });
  };
  const std::vector<uint8_t> all(n, 1);
  if (plan.method == Method::Fast) {
    // Each sigma's averages kept at the queries as they come: a halo point holds one
    // sigma's average at a time, not every sigma's.
    FilterStats stats;
    scope.occupied_cells.assign(plan.fast_cells.begin(), plan.fast_cells.begin() + long(sigmas.size()));
    scope.take = [&](size_t k, const std::vector<double>& at_points) { keep_queries(at_points, G[k]); };
    gaussian_filter_fast(points, all, src.curvature, sigmas, plan.threads, &stats, {}, {}, &scope);
    r.pairs = stats.pairs;
  } else {
    // The exact sweep filters every sigma in one pass over the neighbours.
    FilterStats stats;
    std::vector<std::vector<double>> at_points =
        gaussian_filter(points, all, src.curvature, sigmas, plan.threads, &stats, {}, &scope);
    for (size_t k = 0; k < sigmas.size(); ++k) {
      keep_queries(at_points[k], G[k]);
      std::vector<double>().swap(at_points[k]);
    }
    r.pairs = stats.pairs;
  }
  auto index_of = [&](double unit) {
    return size_t(std::find(units.begin(), units.end(), unit) - units.begin());
  };
  // Each scale's raw map at the query points.
  std::vector<std::vector<double>> raw(scales, std::vector<double>(queries));
  for (size_t k = 0; k < scales; ++k) {
    const std::vector<double>& fine = G[index_of(plan.scales[k])];
    const std::vector<double>& coarse = G[index_of(2 * plan.scales[k])];
    for (size_t q = 0; q < queries; ++q) raw[k][q] = std::fabs(fine[q] - coarse[q]);
  }
  std::vector<std::vector<double>>().swap(G);
  // The own points' candidates for local maxima against their rings (phase 2 needs no more
  // of the tile), each ring the other corners of the point's triangles (a neighbour across
  // an inner edge twice; a corner repeated in a degenerate triangle is no neighbour of
  // itself; an empty ring leaves -infinity, and the point a maximum, as the adjacency's
  // test would): the largest raw value of the ring beside the point's, where the point's
  // is above every neighbour's.
  std::vector<uint32_t> slot(corner.size(), UINT32_MAX);
  uint32_t owned = 0;
  for (size_t i = 0; i < corner.size(); ++i)
    if (query.own[i]) slot[i] = owned++;
  const std::vector<uint32_t>& tri = query.triangles;
  if (tri.size() / 3 > UINT32_MAX / 6)
    throw Error("tiled saliency: a tile of more than 715 million triangles: use more tiles");
  // Each own point's largest ring value per scale, scattered from the triangles in one
  // pass for every scale (on the threads, each owning a range of the points); a point is a
  // candidate where its value is above that largest (above every neighbour's).
  std::vector<double> ring_max(size_t(owned) * scales, -INFINITY);
  parallel_for_owned(owned, plan.threads, [&](size_t lo, size_t hi) {
    for (size_t f = 0; f + 2 < tri.size(); f += 3)
      for (int j = 0; j < 3; ++j) {
        const uint32_t v = tri[f + j], o = slot[v];
        if (o == UINT32_MAX || o < lo || o >= hi) continue;
        double* m = &ring_max[size_t(o) * scales];
        for (int i = 1; i <= 2; ++i) {
          const uint32_t w = tri[f + (j + i) % 3];
          if (w == v) continue;
          for (size_t k = 0; k < scales; ++k) m[k] = std::max(m[k], raw[k][corner[w]]);
        }
      }
  });
  for (size_t k = 0; k < scales; ++k)
    for (size_t i = 0; i < corner.size(); ++i) {
      const uint32_t o = slot[i];
      if (o == UINT32_MAX) continue;
      const double value = raw[k][corner[i]], most = ring_max[size_t(o) * scales + k];
      if (value > most) r.candidates[k].push_back({query.corners[i], value, most});
    }
  std::vector<double>().swap(ring_max);
  // What phase 3 reads: the own points, and with smoothing every query point.
  const size_t kept = plan.smoothed ? queries : owned;
  r.global.reserve(kept);
  r.own.reserve(kept);
  r.curvature.reserve(kept);
  for (auto& k : r.raw) k.reserve(kept);
  for (size_t v = 0; v < n; ++v) {
    if (qi[v] == UINT32_MAX) continue;
    const float* p = &points.positions[3 * v];
    const bool own = tile_of(plan, p) == t;
    if (!own && !plan.smoothed) continue;
    r.global.push_back(src.global[v]);
    if (plan.smoothed) r.positions.insert(r.positions.end(), p, p + 3);
    r.own.push_back(own ? 1 : 0);
    r.curvature.push_back(src.curvature[v]);
    for (size_t k = 0; k < scales; ++k) r.raw[k].push_back(raw[k][qi[v]]);
  }
  return r;
}

std::vector<ScaleMax> tile_scale_max(const TileRaw& tile) {
  std::vector<ScaleMax> out(tile.raw.size());
  // As suppress() picks it: the first maximum in vertex order.
  for (size_t k = 0; k < tile.raw.size(); ++k) {
    ScaleMax& m = out[k];
    for (size_t q = 0; q < tile.global.size(); ++q)
      if (tile.own[q] && (m.vertex == UINT32_MAX || tile.raw[k][q] > m.max)) {
        m.max = tile.raw[k][q];
        m.vertex = tile.global[q];
      }
  }
  return out;
}

void merge_scale_max(std::vector<ScaleMax>& into, const std::vector<ScaleMax>& from) {
  if (into.size() < from.size()) into.resize(from.size());
  for (size_t k = 0; k < from.size(); ++k) {
    const ScaleMax& f = from[k];
    ScaleMax& m = into[k];
    if (f.vertex == UINT32_MAX) continue;
    if (m.vertex == UINT32_MAX || f.max > m.max || (f.max == m.max && f.vertex < m.vertex)) m = f;
  }
}

std::vector<std::vector<LocalMax>> tile_local_maxima(const std::vector<std::vector<MaxCandidate>>& candidates,
                                                     const std::vector<ScaleMax>& max) {
  std::vector<std::vector<LocalMax>> out(candidates.size());
  for (size_t k = 0; k < candidates.size(); ++k) {
    if (!(max[k].max > 0)) continue;  // an all-zero map stays zero: no maxima needed
    for (const MaxCandidate& c : candidates[k]) {
      const double norm = c.value / max[k].max;
      if (norm > c.ring_max / max[k].max) out[k].push_back({c.vertex, norm});
    }
  }
  return out;
}

double mbar_of(std::vector<LocalMax> maxima, const ScaleMax& max) {
  std::sort(maxima.begin(), maxima.end(),
            [](const LocalMax& a, const LocalMax& b) { return a.vertex < b.vertex; });
  double sum = 0;
  size_t others = 0;
  for (const LocalMax& m : maxima) {
    if (m.vertex == max.vertex) continue;
    sum += m.value;
    others++;
  }
  return others > 0 ? sum / double(others) : 0.0;
}

TileResult tile_finish(const TileRaw& tile, const TilePlan& plan, const std::vector<ScaleMax>& max,
                       const std::vector<double>& mbar) {
  TileResult r;
  const size_t nq = tile.global.size();
  r.raw.resize(tile.raw.size());
  // S at every query point, as suppress() and compute_saliency_cpu form it.
  std::vector<double> S(nq, 0.0);
  for (size_t k = 0; k < tile.raw.size(); ++k) {
    if (!(max[k].max > 0)) continue;  // suppress(): zero map
    const double factor = (1.0 - mbar[k]) * (1.0 - mbar[k]);
    for (size_t q = 0; q < nq; ++q) {
      double out = tile.raw[k][q] / max[k].max;
      out *= factor;
      S[q] += out;
    }
  }
  std::vector<double> Sm;
  if (plan.smoothed && nq > 0) {
    Mesh points;
    points.positions = tile.positions;
    const std::vector<uint8_t> all(nq, 1);
    FilterScope scope;
    scope.frame = GridFrame{plan.box, plan.points};
    scope.query = &tile.own;
    const std::vector<double> sigma{3 * plan.eps};
    if (plan.method == Method::Fast) {
      scope.occupied_cells.assign(plan.fast_cells.end() - 1, plan.fast_cells.end());
      Sm = gaussian_filter_fast(points, all, S, sigma, plan.threads, nullptr, {}, {}, &scope)[0];
    } else {
      Sm = gaussian_filter(points, all, S, sigma, plan.threads, nullptr, {}, &scope)[0];
    }
  }
  for (size_t q = 0; q < nq; ++q) {
    if (!tile.own[q]) continue;
    r.global.push_back(tile.global[q]);
    if (!tile.curvature.empty()) r.curvature.push_back(tile.curvature[q]);
    r.saliency.push_back(S[q]);
    if (plan.smoothed) r.smoothed.push_back(Sm[q]);
    for (size_t k = 0; k < tile.raw.size(); ++k) r.raw[k].push_back(tile.raw[k][q]);
  }
  return r;
}

}  // namespace meshsal
