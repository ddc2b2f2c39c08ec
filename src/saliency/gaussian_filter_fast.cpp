#include "saliency/gaussian_filter_fast.h"

#include <algorithm>
#include <atomic>
#include <mutex>
#include <cmath>
#include <thread>
#include <utility>

#include "core/mesh_points.h"
#include "core/parallel.h"
#include "core/parallel_select.h"
#include "saliency/query_groups.h"
#include "saliency/sparse_cells.h"
#include "saliency/spatial_grid.h"
#include "saliency/sweep_kernels.h"

namespace meshsal {

namespace {

using sweep::Aggregates;

// The aggregates of `cells` on a query grid of cells of a quarter of the cutoff radius (as
// in the exact sweep), their floats relative to the frame box's minimum, and (groups, when
// not null) each query group's centroid relative to it. `frame`: the whole mesh's box and
// occupied cells (a tile's grid is then a window of the whole mesh's, so that a query walks
// the same candidates in the same rows and lanes there: the same float sums, the same bits).
Aggregates aggregate(const Mesh& mesh, const SparseCells& cells, const double* values,
                     double query_radius, const GridFrame& frame, unsigned threads,
                     sweep::QueryGroups* groups) {
  const double* anchor = frame.box.min;
  const size_t m = cells.start.size() - 1;
  Mesh centroids;  // of the cells, in cell order: what the grid sorts
  centroids.positions.resize(3 * m);
  parallel_for(m, threads, 4096, [&](size_t begin, size_t end) {
    for (size_t c = begin; c < end; ++c) {
      double p[3] = {0, 0, 0};
      for (uint32_t i = cells.start[c]; i < cells.start[c + 1]; ++i) {
        // The points of the cells ahead, fetched now (in cell order they lie anywhere).
        if (i + 32 < cells.order.size()) __builtin_prefetch(&mesh.positions[3 * size_t(cells.order[i + 32])]);
        for (int a = 0; a < 3; ++a) p[a] += mesh.positions[3 * size_t(cells.order[i]) + a];
      }
      const double n = cells.start[c + 1] - cells.start[c];
      for (int a = 0; a < 3; ++a) centroids.positions[3 * c + a] = float(p[a] / n);
    }
  });
  if (groups) {
    // Each group's centroid: its cells' centroids weighted by their point counts.
    const size_t units = groups->start.size() - 1;
    groups->centroid.assign(3 * units, 0.0);
    parallel_for(units, threads, 4096, [&](size_t begin, size_t end) {
      for (size_t g = begin; g < end; ++g) {
        double q[3] = {0, 0, 0}, n = 0;
        for (uint32_t i = groups->start[g]; i < groups->start[g + 1]; ++i) {
          const size_t c = groups->cell[i];
          const double k = cells.start[c + 1] - cells.start[c];
          for (int d = 0; d < 3; ++d) q[d] += k * (double(centroids.positions[3 * c + d]) - anchor[d]);
          n += k;
        }
        for (int d = 0; d < 3; ++d) groups->centroid[3 * g + d] = q[d] / n;
      }
    });
  }
  Aggregates ag;
  // At most a grid cell per centroid (grid_cell_size allows 4 per point): the cell starts
  // were 16 bytes a centroid at the finest sigma's peak.
  ag.grid = build_grid_order(centroids, std::vector<uint8_t>(m, 1), 0.25 * query_radius, &frame,
                             std::max<double>(1 << 20, double(frame.points)));
  for (int a = 0; a < 3; ++a) ag.anchor[a] = anchor[a];
  // Slot order, in float, padded with far-away empty cells (their squared distance is
  // +inf: never inside the cutoff). The positions first, then the centroids freed, then
  // the counts and sums.
  const size_t padded = m + sweep::kAggregatePad;
  ag.x.assign(padded, 1e30f);
  ag.y.assign(padded, 1e30f);
  ag.z.assign(padded, 1e30f);
  parallel_for(m, threads, 4096, [&](size_t begin, size_t end) {
    for (size_t slot = begin; slot < end; ++slot) {
      const uint32_t c = ag.grid.order[slot];
      ag.x[slot] = float(double(centroids.positions[3 * c]) - anchor[0]);
      ag.y[slot] = float(double(centroids.positions[3 * c + 1]) - anchor[1]);
      ag.z[slot] = float(double(centroids.positions[3 * c + 2]) - anchor[2]);
    }
  });
  std::vector<float>().swap(centroids.positions);
  ag.count.assign(padded, 0.0f);
  ag.sum.assign(padded, 0.0f);
  parallel_for(m, threads, 4096, [&](size_t begin, size_t end) {
    for (size_t slot = begin; slot < end; ++slot) {
      if (slot + 8 < end) __builtin_prefetch(&values[cells.order[cells.start[ag.grid.order[slot + 8]]]]);
      const uint32_t c = ag.grid.order[slot];
      double sum = 0;
      for (uint32_t i = cells.start[c]; i < cells.start[c + 1]; ++i) sum += values[cells.order[i]];
      ag.count[slot] = float(cells.start[c + 1] - cells.start[c]);
      ag.sum[slot] = float(sum);
    }
  });
  return ag;
}

void check_inputs(const Mesh& mesh, const std::vector<uint8_t>& is_point,
                  const std::vector<double>& values, const std::vector<double>& sigmas) {
  if (is_point.size() != mesh.vertex_count() || values.size() != mesh.vertex_count())
    throw Error("Gaussian filter: per-vertex arrays do not match the vertex count");
  if (sigmas.empty()) throw Error("Gaussian filter needs at least one sigma");
  for (double s : sigmas)
    if (!(s > 0) || !std::isfinite(s)) throw Error("Gaussian filter sigma must be positive");
}

// The box of a tile's query vertices (on the threads: a tile's points are a few million).
BoundingBox query_points_box(const Mesh& mesh, const std::vector<uint32_t>& point_list,
                             const std::vector<uint8_t>& query, unsigned threads) {
  BoundingBox query_box;
  for (int a = 0; a < 3; ++a) query_box.min[a] = INFINITY, query_box.max[a] = -INFINITY;
  std::mutex m;
  parallel_for(point_list.size(), threads, 1 << 16, [&](size_t begin, size_t end) {
    BoundingBox b;
    for (int a = 0; a < 3; ++a) b.min[a] = INFINITY, b.max[a] = -INFINITY;
    for (size_t i = begin; i < end; ++i) {
      const uint32_t v = point_list[i];
      if (query[v])
        for (int a = 0; a < 3; ++a) {
          b.min[a] = std::min(b.min[a], double(mesh.positions[3 * size_t(v) + a]));
          b.max[a] = std::max(b.max[a], double(mesh.positions[3 * size_t(v) + a]));
        }
    }
    const std::lock_guard<std::mutex> lock(m);  // (min and max: any order gives the same box)
    for (int a = 0; a < 3; ++a)
      query_box.min[a] = std::min(query_box.min[a], b.min[a]), query_box.max[a] = std::max(query_box.max[a], b.max[a]);
  });
  return query_box;
}

// For each point of `point_list`, one bit per sigma: whether it lies within that sigma's
// reach of the query box (one pass over the positions for every sigma; then each sigma's
// points are a pass over a byte or four a point).
std::vector<uint32_t> reach_bits(const Mesh& mesh, const std::vector<uint32_t>& point_list,
                                 const BoundingBox& query_box, const std::vector<double>& reach, unsigned threads) {
  std::vector<uint32_t> bits(point_list.size());
  parallel_for(point_list.size(), threads, 1 << 16, [&](size_t begin, size_t end) {
    for (size_t i = begin; i < end; ++i) {
      const float* p = &mesh.positions[3 * size_t(point_list[i])];
      uint32_t b = 0;
      for (size_t k = 0; k < reach.size(); ++k) {
        bool in = true;
        for (int a = 0; a < 3 && in; ++a) {
          const double x = p[a];
          in = x >= query_box.min[a] - reach[k] && x <= query_box.max[a] + reach[k];
        }
        b |= uint32_t(in) << k;
      }
      bits[i] = b;
    }
  });
  return bits;
}

// One sigma's progress: the vertices written so far, told from the caller's thread only.
struct SigmaProgress {
  const std::function<void(double)>& progress;
  std::thread::id caller;
  size_t sigma, sigmas, points;
  std::atomic<size_t> done{0};
  void tick(size_t count) {
    size_t finished = done += count;
    if (progress && std::this_thread::get_id() == caller)
      progress((sigma + double(finished) / points) / sigmas);
  }
};

// The query groups that hold one of a tile's query vertices, in order.
std::vector<uint32_t> groups_with_queries(const sweep::QueryGroups& groups, const SparseCells& cells,
                                          const std::vector<uint8_t>& query) {
  const size_t units = groups.start.size() - 1;
  std::vector<uint32_t> wanted;
  for (size_t u = 0; u < units; ++u) {
    bool any = false;
    for (uint32_t i = groups.start[u]; i < groups.start[u + 1] && !any; ++i) {
      const uint32_t c = groups.cell[i];
      for (uint32_t j = cells.start[c]; j < cells.start[c + 1] && !any; ++j) any = query[cells.order[j]];
    }
    if (any) wanted.push_back(uint32_t(u));
  }
  return wanted;
}

// Dense cells: the hot loop per query group (all of them, or a tile's that hold a query
// vertex), with the cutoff's shell `shell` deep (0: none).
void query_groups(sweep::QueryArgs& args, const sweep::QueryGroups& groups, const SparseCells& cells,
                  const std::vector<uint8_t>* query, double shell, unsigned threads,
                  std::atomic<uint64_t>& total_pairs, SigmaProgress& tick) {
  // The hot loops, on the instruction set cpu_path() picks (sweep_kernels.h).
  const sweep::Kernels& kernels = sweep::kernels();
  const double s = args.s, t = shell;
  args.groups = &groups;
  args.shell2 = t > 0 ? (2 * s - t) * (2 * s - t) : INFINITY;
  args.shell_weight = t > 0 ? s * s * std::exp(-2.0) / (2 * s * t) : 0.0;
  const size_t units = groups.start.size() - 1;
  // A tile queries only the groups that hold one of its query vertices.
  std::vector<uint32_t> wanted;
  if (query) wanted = groups_with_queries(groups, cells, *query);
  const size_t count = query ? wanted.size() : units;
  parallel_for(count, threads, 16, [&](size_t begin, size_t end) {
    uint64_t pairs = 0;
    size_t visited = 0;
    if (!query) {
      visited = kernels.query_cells(args, begin, end, &pairs);
    } else {
      for (size_t i = begin; i < end; ++i)
        visited += kernels.query_cells(args, wanted[i], wanted[i] + 1, &pairs);
    }
    total_pairs += pairs;
    tick.tick(visited);
  });
}

// The per-vertex path's visiting order: the (query) points in the order of the cells of
// edge `cell`. `point_list` is made again when an earlier sigma handed it over.
std::vector<uint32_t> visiting_order(const Mesh& mesh, const std::vector<uint8_t>& is_point,
                                     std::vector<uint32_t>& point_list, const BoundingBox& box, double cell,
                                     const std::vector<uint8_t>* query, unsigned threads) {
  if (point_list.empty()) point_list = mesh_point_list(is_point);  // handed over
  std::vector<uint32_t> visit = sort_into_cells(mesh, point_list, box, cell, threads).order;
  if (query)
    visit.erase(std::remove_if(visit.begin(), visit.end(), [&](uint32_t v) { return !(*query)[v]; }),
                visit.end());
  return visit;
}

// Sparse cells: the hot loop per vertex, in `visit` order.
void query_visits(sweep::QueryArgs& args, const std::vector<uint32_t>& visit, unsigned threads,
                  std::atomic<uint64_t>& total_pairs, SigmaProgress& tick) {
  // The hot loops, on the instruction set cpu_path() picks (sweep_kernels.h).
  const sweep::Kernels& kernels = sweep::kernels();
  args.visit = visit.data();
  parallel_for(visit.size(), threads, 512, [&](size_t begin, size_t end) {
    uint64_t pairs = 0;
    kernels.query_vertices(args, begin, end, &pairs);
    total_pairs += pairs;
    tick.tick(end - begin);
  });
}

}  // namespace

double fast_cell_edge(const BoundingBox& box, double sigma, const FastFilterParams& params) {
  return usable_cell(box, sigma / params.cells_per_sigma);
}

std::vector<uint64_t> count_fast_cells(const Mesh& mesh, const std::vector<uint8_t>& is_point,
                                       const std::vector<uint8_t>& own, const BoundingBox& box,
                                       const std::vector<double>& sigmas,
                                       const FastFilterParams& params) {
  const std::vector<uint32_t> point_list = mesh_point_list(is_point);
  std::vector<uint64_t> counts;
  for (double s : sigmas) {
    const SparseCells cells = sort_into_cells(mesh, point_list, box, fast_cell_edge(box, s, params));
    uint64_t owned = 0;
    // Within a cell the points keep vertex order: the first is the lowest index.
    for (size_t c = 0; c + 1 < cells.start.size(); ++c) owned += own[cells.order[cells.start[c]]] ? 1 : 0;
    counts.push_back(owned);
  }
  return counts;
}

std::vector<std::vector<double>> gaussian_filter_fast(
    const Mesh& mesh, const std::vector<uint8_t>& is_point, const std::vector<double>& values,
    const std::vector<double>& sigmas, unsigned threads, FilterStats* stats,
    const std::function<void(double)>& progress, const FastFilterParams& params,
    const FilterScope* scope) {
  check_inputs(mesh, is_point, values, sigmas);
  if (scope && scope->query && scope->occupied_cells.size() != sigmas.size())
    throw Error("internal: a tile's fast filter needs the whole mesh's cell count per sigma");
  if (sigmas.size() > size_t(sweep::kMaxSigmas)) throw Error("Gaussian filter: at most 32 sigmas");
  // Every sigma's array, or (handed over) one reused from sigma to sigma.
  const bool handed = scope && scope->take;
  std::vector<std::vector<double>> out(handed ? 1 : sigmas.size(), std::vector<double>(mesh.vertex_count(), 0.0));
  std::vector<uint32_t> point_list = mesh_point_list(is_point);
  const size_t points = point_list.size();
  if (points == 0) return out;
  // The cells are laid over the whole mesh's points (a tile's scope) or this mesh's.
  const BoundingBox box = scope ? scope->frame.box : mesh_points_bbox(mesh, is_point);
  const double all_points = scope ? double(scope->frame.points) : double(points);
  const std::vector<uint8_t>* query = scope ? scope->query : nullptr;
  // The per-vertex path visits vertices in the order of the finest cells, so that
  // neighbours in a thread's chunk share the cells they read (sorted when first needed).
  const double finest = *std::min_element(sigmas.begin(), sigmas.end());
  std::vector<uint32_t> visit;

  std::atomic<uint64_t> total_pairs{0};
  const std::thread::id caller = std::this_thread::get_id();
  // A tile: each sigma's cells need only the points within its reach of the queries (2 s
  // and the cells around them); the smaller sigmas skip most of the halo.
  std::vector<uint32_t> reached, within;
  if (query) {
    std::vector<double> reach;
    for (double s : sigmas) reach.push_back(2 * s + 3 * fast_cell_edge(box, s, params));
    within = reach_bits(mesh, point_list, query_points_box(mesh, point_list, *query, threads), reach, threads);
  }
  for (size_t k = 0; k < sigmas.size(); ++k) {
    const double s = sigmas[k];
    const double cell = fast_cell_edge(box, s, params);
    const std::vector<uint32_t>* sorted_points = &point_list;
    if (query) {
      parallel_select(
          point_list.size(), threads, [&](size_t i) { return (within[i] >> k) & 1; },
          [&](size_t i) { return point_list[i]; }, reached);
      sorted_points = &reached;
    }
    // The last sigma of a whole mesh hands the list over to its cells (the fast CPU
    // pipeline filters one sigma a call: 4 bytes per point less at its peak).
    const bool hand_over = !query && k + 1 == sigmas.size();
    SparseCells cells = hand_over ? sort_into_cells(mesh, std::move(point_list), box, cell, threads)
                                        : sort_into_cells(mesh, *sorted_points, box, cell, threads);
    if (hand_over) std::vector<uint32_t>().swap(point_list);  // empty for certain
    const double coef = 1.0 / (2 * s * s), cutoff2 = 4 * s * s;
    SigmaProgress tick{progress, caller, k, sigmas.size(), points};
    const size_t m = cells.key.size();
    const double all_cells = scope && !scope->occupied_cells.empty() ? double(scope->occupied_cells[k]) : double(m);
    // Dense cells: the sums and their gradients once at each query group's centroid,
    // extrapolated linearly to the group's vertices (cost per group, not per vertex); a
    // tile's only at the groups holding a query vertex.
    const bool dense = all_points >= params.points_per_query_cell * all_cells;
    sweep::QueryGroups groups;
    if (dense) groups = group_cells(cells.key, cells.dims, params.query_factor, threads);
    std::vector<uint64_t>().swap(cells.key);  // grouped: 8 bytes a cell less from here on
    const GridFrame cell_frame{box, uint64_t(all_cells)};
    const Aggregates ag = aggregate(mesh, cells, values.data(), 2 * s, cell_frame, threads, dense ? &groups : nullptr);
    std::vector<double>& into = out[handed ? 0 : k];
    sweep::QueryArgs args{&mesh, &ag, &cells, nullptr, nullptr, values.data(), s, coef, cutoff2,
                          1.0 / (s * s), INFINITY, 0.0, into.data()};
    if (dense) {
      // The cutoff's shell: params.shell_cells cells deep (0: none).
      query_groups(args, groups, cells, query, params.shell_cells * cell, threads, total_pairs, tick);
    } else {
      if (visit.empty())
        visit = visiting_order(mesh, is_point, point_list, box, fast_cell_edge(box, finest, params), query, threads);
      query_visits(args, visit, threads, total_pairs, tick);
    }
    if (handed) scope->take(k, into);
  }
  if (handed) out.clear();
  if (stats) stats->pairs = total_pairs;
  return out;
}

double estimate_sweep_pairs(const Mesh& mesh, const std::vector<uint8_t>& is_point,
                            double radius) {
  const BoundingBox box = mesh_points_bbox(mesh, is_point);
  const double cell = usable_cell(box, radius);
  const SparseCells cells = sort_into_cells(mesh, mesh_point_list(is_point), box, cell, 0);
  const size_t points = cells.order.size();
  const size_t samples = std::min<size_t>(256, points);
  const double r2 = radius * radius;
  auto range_of = [&](uint64_t key) {
    auto it = std::lower_bound(cells.key.begin(), cells.key.end(), key);
    if (it == cells.key.end() || *it != key) return std::pair<uint32_t, uint32_t>{0, 0};
    size_t c = size_t(it - cells.key.begin());
    return std::pair<uint32_t, uint32_t>{cells.start[c], cells.start[c + 1]};
  };
  double counted = 0;
  for (size_t t = 0; t < samples; ++t) {
    const uint32_t v = cells.order[(t * points) / samples];
    const float* p = &mesh.positions[3 * v];
    const uint64_t key = cell_key(box, cell, cells.dims, p);
    const int64_t c[3] = {int64_t(key % cells.dims[0]), int64_t(key / cells.dims[0] % cells.dims[1]),
                          int64_t(key / cells.dims[0] / cells.dims[1])};
    const int64_t d[3] = {int64_t(cells.dims[0]), int64_t(cells.dims[1]), int64_t(cells.dims[2])};
    // Every point within the radius lies in one of the 27 cells around v's.
    for (int dz = -1; dz <= 1; ++dz)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          int64_t x = c[0] + dx, y = c[1] + dy, z = c[2] + dz;
          if (x < 0 || y < 0 || z < 0 || x >= d[0] || y >= d[1] || z >= d[2]) continue;
          auto [b, e] = range_of(uint64_t((z * d[1] + y) * d[0] + x));
          for (uint32_t i = b; i < e; ++i) {
            const float* q = &mesh.positions[3 * cells.order[i]];
            double ex = double(q[0]) - p[0], ey = double(q[1]) - p[1], ez = double(q[2]) - p[2];
            counted += (ex * ex + ey * ey + ez * ez < r2) ? 1 : 0;
          }
        }
  }
  return samples ? counted / samples * points : 0;
}

}  // namespace meshsal
