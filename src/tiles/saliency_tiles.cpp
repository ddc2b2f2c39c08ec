// The phases of a tiled saliency run (saliency_tiles.h), each on one tile.
#include "tiles/saliency_tiles.h"

#include <algorithm>
#include <cmath>

#include "core/adjacency.h"
#include "core/radix_sort.h"
#include "saliency/curvature.h"
#include "saliency/gaussian_filter.h"
#include "saliency/gaussian_filter_fast.h"
#include "saliency/saliency.h"

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

size_t tile_of(const TilePlan& plan, const float* p) {
  size_t c[3];
  for (int a = 0; a < 3; ++a) {
    const double f = std::floor((double(p[a]) - plan.box.min[a]) / plan.tile_edge);
    c[a] = size_t(std::clamp(f, 0.0, double(plan.tiles[a] - 1)));
  }
  return (c[2] * plan.tiles[1] + c[1]) * plan.tiles[0] + c[0];
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

TileMesh assemble_tile(const TilePlan& plan, size_t t, const TileSource& source) {
  // The tile's bucket: its own points and their 1-rings (every corner of those triangles).
  TileMesh tile;
  std::vector<TileFace> faces;
  source.bucket(t, faces);
  distinct_faces(faces);
  Corners c;
  corners_of(faces, source, c);
  BoundingBox own_box = empty_box(), query_box = empty_box();
  for (size_t i = 0; i < c.ids.size(); ++i) {
    grow(query_box, &c.pos[3 * i]);
    if (tile_of(plan, &c.pos[3 * i]) == t) grow(own_box, &c.pos[3 * i]);
  }
  if (own_box.empty()) return tile;
  BoundingBox source_box;
  for (int a = 0; a < 3; ++a) {
    query_box.min[a] = std::min(query_box.min[a], own_box.min[a] - plan.query_margin);
    query_box.max[a] = std::max(query_box.max[a], own_box.max[a] + plan.query_margin);
    source_box.min[a] = query_box.min[a] - plan.source_margin;
    source_box.max[a] = query_box.max[a] + plan.source_margin;
  }
  // Every triangle with a corner among the source points: in the bucket of a tile whose
  // cube meets the source box.
  faces.clear();
  int lo[3], hi[3];
  for (int a = 0; a < 3; ++a) {
    auto cell = [&](double x) {
      return int(std::clamp(std::floor((x - plan.box.min[a]) / plan.tile_edge), 0.0, double(plan.tiles[a] - 1)));
    };
    lo[a] = cell(source_box.min[a]);
    hi[a] = cell(source_box.max[a]);
  }
  for (int z = lo[2]; z <= hi[2]; ++z)
    for (int y = lo[1]; y <= hi[1]; ++y)
      for (int x = lo[0]; x <= hi[0]; ++x) source.bucket((size_t(z) * plan.tiles[1] + y) * plan.tiles[0] + x, faces);
  distinct_faces(faces);
  corners_of(faces, source, c);
  std::vector<uint8_t> inside(c.ids.size());
  for (size_t i = 0; i < c.ids.size(); ++i) inside[i] = in_box(&c.pos[3 * i], source_box, 0.0) ? 1 : 0;
  // The sub-mesh: the triangles kept in the mesh's order, their vertices in vertex order.
  std::vector<uint32_t> kept, number(c.ids.size(), UINT32_MAX);
  for (size_t f = 0; f < faces.size(); ++f) {
    const uint32_t* l = &c.local[3 * f];
    if (!inside[l[0]] && !inside[l[1]] && !inside[l[2]]) continue;
    kept.push_back(uint32_t(f));
    for (int k = 0; k < 3; ++k) number[l[k]] = 0;
  }
  for (size_t i = 0; i < c.ids.size(); ++i) {
    if (number[i] == UINT32_MAX) continue;
    number[i] = uint32_t(tile.global.size());
    tile.global.push_back(c.ids[i]);
    const float* p = &c.pos[3 * i];
    tile.mesh.positions.insert(tile.mesh.positions.end(), p, p + 3);
    const bool own = tile_of(plan, p) == t;
    tile.own.push_back(own ? 1 : 0);
    tile.own_count += own ? 1 : 0;
    tile.query.push_back(in_box(p, query_box, 0.0) ? 1 : 0);
  }
  tile.mesh.triangles.reserve(3 * kept.size());
  for (uint32_t f : kept)
    for (int k = 0; k < 3; ++k) tile.mesh.triangles.push_back(number[c.local[3 * size_t(f) + k]]);
  return tile;
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

TilePlan cell_count_plan(const TilePlan& plan) {
  TilePlan p = plan;
  double widest = 0;
  for (double s : tile_cell_sigmas(plan)) widest = std::max(widest, fast_cell_edge(plan.box, s));
  p.query_margin = 0;
  p.source_margin = 2 * widest;
  return p;
}

std::vector<uint64_t> count_tile_cells(const TileMesh& tile, const TilePlan& plan) {
  const std::vector<double> sigmas = tile_cell_sigmas(plan);
  if (tile.own_count == 0) return std::vector<uint64_t>(sigmas.size(), 0);
  // Only the cells of own points are counted, and each lies within a cell of its point:
  // the points beyond the own box and two of the largest cells need not be sorted.
  BoundingBox own_box = empty_box();
  for (size_t v = 0; v < tile.own.size(); ++v)
    if (tile.own[v]) grow(own_box, &tile.mesh.positions[3 * v]);
  double widest = 0;
  for (double s : sigmas) widest = std::max(widest, fast_cell_edge(plan.box, s));
  std::vector<uint8_t> near = referenced_vertices(tile.mesh);
  for (size_t v = 0; v < near.size(); ++v)
    near[v] = near[v] && in_box(&tile.mesh.positions[3 * v], own_box, 2 * widest);
  return count_fast_cells(tile.mesh, near, tile.own, plan.box, sigmas);
}

namespace {

// The own query points' 1-rings (r.ring, r.ring_offsets, in query numbers, own points in
// vertex order) straight from the triangles: each triangle adds its two other corners to
// each own corner's ring, so a neighbour across an inner edge comes twice. The local-maximum
// test (strictly above every neighbour) reads a ring as a set, so that is the same answer
// as the adjacency's ring, at a pass over the triangles.
void triangle_rings(const Mesh& mesh, const std::vector<uint8_t>& own, const std::vector<uint32_t>& qi, TileRaw& r) {
  const size_t n = mesh.vertex_count();
  std::vector<uint32_t> slot(n, UINT32_MAX);  // own query point -> its ring's number
  uint32_t owned = 0;
  for (size_t v = 0; v < n; ++v)
    if (qi[v] != UINT32_MAX && own[v]) slot[v] = owned++;
  // Two passes of one loop: count, then fill. A corner repeated in a degenerate triangle is
  // no neighbour of itself (as in the adjacency).
  const uint32_t* t = mesh.triangles.data();
  const size_t faces = mesh.triangles.size() / 3;
  std::vector<uint32_t> offsets(size_t(owned) + 1, 0), ring, fill;
  for (int pass = 0; pass < 2; ++pass) {
    if (pass == 1) {
      for (size_t o = 0; o < owned; ++o) offsets[o + 1] += offsets[o];
      ring.resize(offsets.back());
      fill.assign(offsets.begin(), offsets.end() - 1);
    }
    for (size_t f = 0; f < faces; ++f)
      for (int k = 0; k < 3; ++k) {
        const uint32_t v = t[3 * f + k], o = slot[v];
        if (o == UINT32_MAX) continue;
        for (int j = 1; j <= 2; ++j) {
          const uint32_t w = t[3 * f + (k + j) % 3];
          if (w == v) continue;
          if (pass == 0) {
            ++offsets[o + 1];
            continue;
          }
          const uint32_t u = qi[w];
          if (u == UINT32_MAX) throw Error("internal: a tile's halo misses a 1-ring neighbour");
          ring[fill[o]++] = u;
        }
      }
  }
  r.ring = std::move(ring);
  r.ring_offsets = std::move(offsets);
}

}  // namespace

TileRaw tile_raw_maps(TileMesh tile, const TilePlan& plan) {
  TileRaw r;
  r.raw.resize(plan.scales.size());
  if (tile.own_count == 0) {
    r.ring_offsets.push_back(0);
    return r;
  }
  Mesh& mesh = tile.mesh;
  const size_t n = mesh.vertex_count();
  const std::vector<uint8_t> is_point = referenced_vertices(mesh);
  // The query points, in whole-mesh order.
  std::vector<uint32_t> qi(n, UINT32_MAX);
  for (size_t v = 0; v < n; ++v) {
    if (!tile.query[v] || !is_point[v]) continue;
    qi[v] = uint32_t(r.global.size());
    r.global.push_back(tile.global[v]);
    r.positions.insert(r.positions.end(), &mesh.positions[3 * v], &mesh.positions[3 * v + 3]);
    r.own.push_back(tile.own[v]);
  }
  // The same stages as compute_saliency_cpu, on the sub-mesh; the 1-rings and the triangles
  // go once the curvature is known (the averages are the peak).
  std::vector<double> curvature;
  if (plan.method == Method::Fast) {
    // The fast method's curvature needs no 1-rings (saliency_fast_cpu.cpp), and the local
    // maxima need only the own points': taken from their triangles, not from the whole
    // sub-mesh's adjacency (its halo is most of it).
    curvature = mean_curvature_morton(mesh, plan.box, plan.threads);
    triangle_rings(mesh, tile.own, qi, r);
  } else {
    const Adjacency adj = build_adjacency(mesh, plan.threads);
    // Each method's curvature as the whole mesh computes it (saliency_cpu.cpp,
    // saliency_fast_cpu.cpp): an own vertex has all its triangles here, so the same bits.
    curvature = mean_curvature(mesh, adj, vertex_normals(mesh, plan.threads), plan.threads);
    // Own points' 1-rings: every neighbour is a query point (the query box holds the rings).
    r.ring_offsets.push_back(0);
    for (size_t v = 0; v < n; ++v) {
      if (qi[v] == UINT32_MAX || !tile.own[v]) continue;
      for (uint32_t e = adj.offsets[v]; e < adj.offsets[v + 1]; ++e) {
        const uint32_t u = qi[adj.neighbors[e]];
        if (u == UINT32_MAX) throw Error("internal: a tile's halo misses a 1-ring neighbour");
        r.ring.push_back(u);
      }
      r.ring_offsets.push_back(uint32_t(r.ring.size()));
    }
  }
  std::vector<uint32_t>().swap(mesh.triangles);
  for (size_t v = 0; v < n; ++v)
    if (qi[v] != UINT32_MAX) r.curvature.push_back(curvature[v]);
  const std::vector<double> units = filter_sigma_units(plan.scales);
  const std::vector<double> sigmas = filter_sigmas(plan);
  FilterScope scope;
  scope.frame = frame_of(plan);
  scope.query = &tile.query;
  FilterStats stats;
  std::vector<std::vector<double>> G;
  if (plan.method == Method::Fast) {
    scope.occupied_cells.assign(plan.fast_cells.begin(), plan.fast_cells.begin() + sigmas.size());
    G = gaussian_filter_fast(mesh, is_point, curvature, sigmas, plan.threads, &stats, {}, {}, &scope);
  } else {
    G = gaussian_filter(mesh, is_point, curvature, sigmas, plan.threads, &stats, {}, &scope);
  }
  r.pairs = stats.pairs;
  auto index_of = [&](double unit) {
    return size_t(std::find(units.begin(), units.end(), unit) - units.begin());
  };
  for (size_t k = 0; k < plan.scales.size(); ++k) {
    const std::vector<double>& fine = G[index_of(plan.scales[k])];
    const std::vector<double>& coarse = G[index_of(2 * plan.scales[k])];
    for (size_t v = 0; v < n; ++v)
      if (qi[v] != UINT32_MAX) r.raw[k].push_back(std::fabs(fine[v] - coarse[v]));
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

std::vector<std::vector<LocalMax>> tile_local_maxima(const TileRaw& tile,
                                                     const std::vector<ScaleMax>& max) {
  std::vector<std::vector<LocalMax>> out(tile.raw.size());
  const size_t nq = tile.global.size();
  std::vector<double> norm(nq);
  for (size_t k = 0; k < tile.raw.size(); ++k) {
    if (!(max[k].max > 0)) continue;  // an all-zero map stays zero: no maxima needed
    for (size_t q = 0; q < nq; ++q) norm[q] = tile.raw[k][q] / max[k].max;
    size_t o = 0;  // own point number (ring_offsets index)
    for (size_t q = 0; q < nq; ++q) {
      if (!tile.own[q]) continue;
      bool is_max = true;
      for (uint32_t e = tile.ring_offsets[o]; e < tile.ring_offsets[o + 1] && is_max; ++e)
        is_max = norm[q] > norm[tile.ring[e]];
      ++o;
      if (is_max) out[k].push_back({tile.global[q], norm[q]});
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
    r.curvature.push_back(tile.curvature[q]);
    r.saliency.push_back(S[q]);
    if (plan.smoothed) r.smoothed.push_back(Sm[q]);
    for (size_t k = 0; k < tile.raw.size(); ++k) r.raw[k].push_back(tile.raw[k][q]);
  }
  return r;
}

}  // namespace meshsal
