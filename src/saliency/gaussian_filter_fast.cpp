#include "saliency/gaussian_filter_fast.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <thread>
#include <utility>

#include "core/mesh_points.h"
#include "core/parallel.h"
#include "core/exp_poly7.h"
#include "core/simd_exp.h"
#include "saliency/sparse_cells.h"
#include "saliency/spatial_grid.h"

namespace meshsal {

namespace {

// One sigma's aggregates, in the query grid's slot order: centroid (relative to the grid
// origin), point count and value sum, padded by 4 empty far-away cells for 4-wide loads.
struct Aggregates {
  SpatialGrid grid;  // over the centroids; grid.x/y/z are the centroids
  std::vector<double> count, sum;
  std::vector<float> centroid;  // x,y,z per cell in SparseCells order (model coordinates)
};

Aggregates aggregate(const Mesh& mesh, const SparseCells& cells, const double* values,
                     double query_radius, unsigned threads) {
  const size_t m = cells.key.size();
  Mesh centroids;
  centroids.positions.resize(3 * m);
  std::vector<double> count(m), sum(m);
  parallel_for(m, threads, 4096, [&](size_t begin, size_t end) {
    for (size_t c = begin; c < end; ++c) {
      double p[3] = {0, 0, 0}, s = 0;
      for (uint32_t i = cells.start[c]; i < cells.start[c + 1]; ++i) {
        uint32_t v = cells.order[i];
        for (int a = 0; a < 3; ++a) p[a] += mesh.positions[3 * v + a];
        s += values[v];
      }
      const double n = cells.start[c + 1] - cells.start[c];
      for (int a = 0; a < 3; ++a) centroids.positions[3 * c + a] = float(p[a] / n);
      count[c] = n;
      sum[c] = s;
    }
  });
  Aggregates ag;
  // Query cells of a quarter of the cutoff radius, as in the exact sweep.
  ag.grid = build_spatial_grid(centroids, std::vector<uint8_t>(m, 1), 0.25 * query_radius);
  ag.centroid = std::move(centroids.positions);
  ag.count.assign(m + 4, 0.0);
  ag.sum.assign(m + 4, 0.0);
  for (size_t s = 0; s < m; ++s) {
    ag.count[s] = count[ag.grid.order[s]];
    ag.sum[s] = sum[ag.grid.order[s]];
  }
  return ag;
}

inline double hsum(v4d v) { return (v[0] + v[1]) + (v[2] + v[3]); }

// The weights inside the cutoff: exp_neg_cutoff() of core/exp_poly7.h, exp(-x) on
// 0 <= x < 2 as (exp(-x/4))^4 with the degree-7 Taylor polynomial for exp(-x/4) (relative
// error at most 6.05e-7, far below the cells' own error).

// The weighted sums at a query point q, and (Grad) their gradients in q, for extrapolating
// from a cell's centroid to the vertices in that cell.
struct CellSums {
  double num = 0, den = 0;
  double gnum[3] = {0, 0, 0}, gden[3] = {0, 0, 0};  // times sigma^2
};

// sum count*w and sum sum*w over the aggregates with |centroid - q| < 2 sigma.
template <bool Grad>
CellSums sweep_cells(const Aggregates& ag, const double q[3], double coef, double cutoff2,
                     uint64_t* pairs) {
  const SpatialGrid& g = ag.grid;
  const double xi = q[0] - g.origin[0], yi = q[1] - g.origin[1], zi = q[2] - g.origin[2];
  const v4d lane = {0, 1, 2, 3}, zero = v4d_splat(0.0), one = v4d_splat(1.0);
  const v4d vx = v4d_splat(xi), vy = v4d_splat(yi), vz = v4d_splat(zi);
  const v4d vcoef = v4d_splat(coef), vcut = v4d_splat(cutoff2);
  v4d n = zero, d = zero, np = zero;
  v4d gn[3] = {zero, zero, zero}, gd[3] = {zero, zero, zero};
  for_each_row_in_ball(g, xi, yi, zi, cutoff2, [&](size_t jb, size_t je) {
    for (size_t j = jb; j < je; j += 4) {
      v4d ex = v4d_load(&g.x[j]) - vx, ey = v4d_load(&g.y[j]) - vy, ez = v4d_load(&g.z[j]) - vz;
      v4d d2 = ex * ex + ey * ey + ez * ez;
      v4i in = (lane < v4d_splat(double(je - j))) & (d2 < vcut);
      v4d w = in ? exp_neg_cutoff(d2 * vcoef) : zero;
      v4d wn = w * v4d_load(&ag.sum[j]), wd = w * v4d_load(&ag.count[j]);
      n += wn;
      d += wd;
      np += in ? one : zero;
      if (Grad) {
        // d/dq w(|x - q|) = w (x - q) / sigma^2; the 1/sigma^2 is applied by the caller.
        gn[0] += wn * ex, gn[1] += wn * ey, gn[2] += wn * ez;
        gd[0] += wd * ex, gd[1] += wd * ey, gd[2] += wd * ez;
      }
    }
  });
  CellSums r;
  r.num = hsum(n);
  r.den = hsum(d);
  if (Grad)
    for (int a = 0; a < 3; ++a) r.gnum[a] = hsum(gn[a]), r.gden[a] = hsum(gd[a]);
  *pairs += uint64_t(hsum(np));
  return r;
}

void check_inputs(const Mesh& mesh, const std::vector<uint8_t>& is_point,
                  const std::vector<double>& values, const std::vector<double>& sigmas) {
  if (is_point.size() != mesh.vertex_count() || values.size() != mesh.vertex_count())
    throw Error("Gaussian filter: per-vertex arrays do not match the vertex count");
  if (sigmas.empty()) throw Error("Gaussian filter needs at least one sigma");
  for (double s : sigmas)
    if (!(s > 0) || !std::isfinite(s)) throw Error("Gaussian filter sigma must be positive");
}

}  // namespace

std::vector<std::vector<double>> gaussian_filter_fast(
    const Mesh& mesh, const std::vector<uint8_t>& is_point, const std::vector<double>& values,
    const std::vector<double>& sigmas, unsigned threads, FilterStats* stats,
    const std::function<void(double)>& progress, const FastFilterParams& params) {
  check_inputs(mesh, is_point, values, sigmas);
  const BoundingBox box = mesh_points_bbox(mesh, is_point);
  std::vector<std::vector<double>> out(sigmas.size(), std::vector<double>(mesh.vertex_count(), 0.0));

  const std::vector<uint32_t> point_list = mesh_point_list(is_point);
  const size_t points = point_list.size();
  // The per-vertex path visits vertices in the order of the finest cells, so that
  // neighbours in a thread's chunk share the cells they read (sorted when first needed).
  const double finest = *std::min_element(sigmas.begin(), sigmas.end());
  std::vector<uint32_t> visit;

  std::atomic<uint64_t> total_pairs{0};
  const std::thread::id caller = std::this_thread::get_id();
  for (size_t k = 0; k < sigmas.size(); ++k) {
    const double s = sigmas[k];
    const double cell = usable_cell(box, s / params.cells_per_sigma);
    const SparseCells cells = sort_into_cells(mesh, point_list, box, cell, threads);
    const Aggregates ag = aggregate(mesh, cells, values.data(), 2 * s, threads);
    const double coef = 1.0 / (2 * s * s), cutoff2 = 4 * s * s;
    std::atomic<size_t> done{0};
    std::vector<double>& o = out[k];
    auto tick = [&](size_t count) {
      size_t finished = done += count;
      if (progress && std::this_thread::get_id() == caller)
        progress((k + double(finished) / points) / sigmas.size());
    };
    const size_t m = ag.count.size() - 4;
    if (double(points) >= params.points_per_query_cell * double(m)) {
      // Dense cells: the sums and their gradients once at each centroid, extrapolated
      // linearly to the cell's vertices (cost per cell, not per vertex).
      parallel_for(m, threads, 64, [&](size_t begin, size_t end) {
        uint64_t pairs = 0;
        size_t visited = 0;
        for (size_t c = begin; c < end; ++c) {
          const double q[3] = {ag.centroid[3 * c], ag.centroid[3 * c + 1], ag.centroid[3 * c + 2]};
          const CellSums cs = sweep_cells<true>(ag, q, coef, cutoff2, &pairs);
          for (uint32_t i = cells.start[c]; i < cells.start[c + 1]; ++i) {
            const uint32_t v = cells.order[i];
            double num = cs.num, den = cs.den;
            for (int a = 0; a < 3; ++a) {
              const double dv = (double(mesh.positions[3 * v + a]) - q[a]) / (s * s);
              num += cs.gnum[a] * dv, den += cs.gden[a] * dv;
            }
            // den > 0 unless the extrapolation overshoots; then the centroid's average.
            o[v] = den > 0 ? num / den : cs.num / cs.den;
          }
          visited += cells.start[c + 1] - cells.start[c];
        }
        total_pairs += pairs;
        tick(visited);
      });
      continue;
    }
    if (visit.empty())
      visit = sort_into_cells(mesh, point_list, box,
                              usable_cell(box, finest / params.cells_per_sigma), threads).order;
    parallel_for(points, threads, 512, [&](size_t begin, size_t end) {
      uint64_t pairs = 0;
      for (size_t i = begin; i < end; ++i) {
        const uint32_t v = visit[i];
        const double q[3] = {mesh.positions[3 * v], mesh.positions[3 * v + 1],
                             mesh.positions[3 * v + 2]};
        const CellSums cs = sweep_cells<false>(ag, q, coef, cutoff2, &pairs);
        // den > 0: the vertex's own cell's centroid is within sqrt(3)/6 sigma of it.
        o[v] = cs.den > 0 ? cs.num / cs.den : values[v];
      }
      total_pairs += pairs;
      tick(end - begin);
    });
  }
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
