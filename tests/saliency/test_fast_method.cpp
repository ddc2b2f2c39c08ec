// --method fast (SPEC 5): the cell-aggregate Gaussian averages held to the exact method, on
// synthetic meshes and two shared scans, and method auto's pair budget.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>

#include "meshsal/meshsal.h"
#include "core/mesh_points.h"
#include "cli/synthetic.h"
#include "saliency/gaussian_filter.h"
#include "saliency/gaussian_filter_fast.h"
#include "saliency/filter_scope.h"
#include "saliency/method_error.h"
#include "saliency/saliency.h"
#include "saliency/sparse_cells.h"
#include "test_util.h"

using namespace meshsal;
using meshsal_test::check_sphere_raw_maps;
using meshsal_test::mean_over;

namespace {

SaliencyOptions fast_options() {
  SaliencyOptions o;
  o.backend = Backend::Cpu;
  o.method = Method::Fast;
  return o;
}

// Fast against exact on a shared scan: the targets of SPEC 5.
void check_scan(const std::string& path, double min_correlation, double min_overlap) {
  Mesh m = load_mesh(path);
  SaliencyOptions exact;
  exact.backend = Backend::Cpu;
  SaliencyResult e = compute_saliency(m, exact);
  SaliencyResult f = compute_saliency(m, fast_options());
  CHECK(e.method == Method::Exact);
  CHECK(f.method == Method::Fast);
  MethodError err = method_error(e, f);
  INFO(path << ": correlation " << err.correlation << ", top-30% overlap " << err.top30_overlap);
  CHECK(err.correlation >= min_correlation);
  CHECK(err.top30_overlap >= min_overlap);
  for (size_t i = 0; i < err.raw_mean.size(); ++i) {
    INFO("raw map " << i << ": mean " << err.raw_mean[i] << ", max " << err.raw_max[i]);
    CHECK(err.raw_mean[i] < 0.01);
    CHECK(err.raw_max[i] < 0.15);
  }
}

}  // namespace

TEST_CASE("fast filter: close to the brute-force averages on a bumpy sphere", "[fast]") {
  Mesh m = make_bumpy_sphere(4);
  std::vector<uint8_t> is_point = referenced_vertices(m);
  SaliencyResult s = compute_saliency_cpu(m, {});
  const double eps = s.eps;
  const std::vector<double> sigmas{2 * eps, 6 * eps, 12 * eps};
  auto exact = gaussian_filter_bruteforce(m, is_point, s.curvature, sigmas);
  FilterStats stats;
  auto fast = gaussian_filter_fast(m, is_point, s.curvature, sigmas, 0, &stats);
  double hmax = 0;
  for (double h : s.curvature) hmax = std::max(hmax, std::fabs(h));
  for (size_t k = 0; k < sigmas.size(); ++k) {
    double worst = 0, sum = 0;
    for (size_t v = 0; v < m.vertex_count(); ++v) {
      const double d = std::fabs(fast[k][v] - exact[k][v]) / hmax;
      worst = std::max(worst, d), sum += d;
    }
    INFO("sigma " << sigmas[k] / eps << " eps: mean " << sum / m.vertex_count() << ", max " << worst
                  << " of max |H|");
    CHECK(sum / m.vertex_count() < 0.01);
    CHECK(worst < 0.05);
  }
  // The pairs it counts are (query, cell) pairs with the cell's centroid within 2 sigma of
  // the query. A cell holds at least one point, all within its diagonal d = sqrt(3) h of the
  // centroid (h: usable_cell(box, sigma / 6)), and distinct cells hold distinct points. So a
  // query at vertex v counts at most the points within 2 sigma + d of v, and at least its own
  // cell (d < 2 sigma). Per query group (a query at the centroid of the cells inside one
  // cell of 2 cells per axis, within 2d of any vertex of the group), at most the points
  // within 2 sigma + 3d of one of its vertices. Where every cell
  // holds one point the centroids are the points: the exact count at 2 sigma, to the pair.
  const BoundingBox box = mesh_points_bbox(m, is_point);
  const std::vector<uint32_t> point_list = mesh_point_list(is_point);
  const double cells_per_sigma = FastFilterParams{}.cells_per_sigma;
  bool one_point_per_cell = true;
  for (double sigma : sigmas) {
    const SparseCells cells = sort_into_cells(m, point_list, box, usable_cell(box, sigma / cells_per_sigma), 0);
    for (size_t c = 0; c + 1 < cells.start.size(); ++c) one_point_per_cell &= cells.start[c + 1] - cells.start[c] == 1;
  }
  auto pair_bound = [&](double diagonals) {
    uint64_t n = 0;
    for (double sigma : sigmas) {
      const double d = std::sqrt(3.0) * usable_cell(box, sigma / cells_per_sigma);
      n += meshsal_test::pairs_within(m, is_point, 2 * sigma + diagonals * d);
    }
    return n;
  };
  const uint64_t points = point_list.size(), exact_pairs = pair_bound(0);
  FastFilterParams per_vertex;
  per_vertex.points_per_query_cell = INFINITY;
  FilterStats vertex_stats;
  gaussian_filter_fast(m, is_point, s.curvature, sigmas, 0, &vertex_stats, {}, per_vertex);
  INFO("pairs: default " << stats.pairs << ", per vertex " << vertex_stats.pairs << ", exact at 2 sigma "
                         << exact_pairs << ", bounds " << pair_bound(1) << " (per vertex), " << pair_bound(2));
  CHECK(vertex_stats.pairs >= sigmas.size() * points);
  CHECK(vertex_stats.pairs <= pair_bound(1));
  CHECK(stats.pairs >= sigmas.size());
  REQUIRE(FastFilterParams{}.query_factor == 2);
  CHECK(stats.pairs <= pair_bound(3));
  // This mesh's cells (h <= 2 eps) are finer than its vertex spacing (~6 eps): one point each.
  CHECK(one_point_per_cell);
  if (one_point_per_cell) {
    CHECK(std::llabs(int64_t(vertex_stats.pairs) - int64_t(exact_pairs)) <= int64_t(exact_pairs / 1000000));
    CHECK(stats.pairs == vertex_stats.pairs);
  }
}

TEST_CASE("fast: sphere raw maps stay near zero", "[fast]") {
  const double r = 3.0;
  check_sphere_raw_maps(compute_saliency(make_sphere(r, 5), fast_options()), r);
}

TEST_CASE("fast: the bump plane's saliency maximum is on the bump", "[fast]") {
  const double size = 4.0, width = 0.12;
  Mesh m = make_plane_with_bump(size, 160, 0.15, width);
  SaliencyResult s = compute_saliency(m, fast_options());
  size_t best = 0;
  double best_value = -1;
  for (size_t v = 0; v < m.vertex_count(); ++v) {
    double x = m.positions[3 * v], y = m.positions[3 * v + 1];
    if (std::fabs(x) > 0.4 * size || std::fabs(y) > 0.4 * size) continue;
    if (s.saliency[v] > best_value) best_value = s.saliency[v], best = v;
  }
  double x = m.positions[3 * best], y = m.positions[3 * best + 1];
  INFO("maximum " << best_value << " at (" << x << ", " << y << ")");
  CHECK(best_value > 0);
  CHECK(std::hypot(x, y) < 3 * width);
}

TEST_CASE("fast: the bumpy sphere's unique feature beats the repeated bumps", "[fast]") {
  std::vector<uint8_t> feature, bumps;
  Mesh m = make_bumpy_sphere(6, &feature, &bumps);
  SaliencyResult s = compute_saliency(m, fast_options());
  const double f = mean_over(s.saliency, feature), b = mean_over(s.saliency, bumps);
  INFO("saliency: feature " << f << ", bumps " << b);
  CHECK(f > 1.5 * b);
}

TEST_CASE("fast against exact: bunny_36k", "[fast]") {
  MESHSAL_REQUIRE_MESH(path, "bunny_36k.obj");
  check_scan(path, 0.999, 0.98);
}

TEST_CASE("fast against exact: dragon_50k", "[fast]") {
  MESHSAL_REQUIRE_MESH(path, "dragon_50k.ply");
  check_scan(path, 0.999, 0.98);
}

TEST_CASE("method error: identical results score 1, a shuffled one does not", "[fast]") {
  SaliencyResult a = compute_saliency_cpu(make_bumpy_sphere(3), {});
  MethodError same = method_error(a, a);
  CHECK(same.correlation == Approx(1.0));
  CHECK(same.top30_overlap == 1.0);
  for (double x : same.raw_max) CHECK(x == 0.0);
  SaliencyResult b = a;
  std::reverse(b.saliency.begin(), b.saliency.end());
  b.raw.back().assign(b.raw.back().size(), 0.0);
  MethodError off = method_error(a, b);
  CHECK(off.correlation < 0.5);
  CHECK(off.top30_overlap < 0.6);
  CHECK(off.raw_max.back() == Approx(1.0));
}

TEST_CASE("method auto: exact under the pair budget, fast with a notice above it", "[fast]") {
  Mesh m = make_bumpy_sphere(5);  // ~10k vertices
  std::vector<std::string> notices;
  SaliencyOptions o;
  o.backend = Backend::Cpu;
  o.method = Method::Auto;
  o.notice = [&](const std::string& line) { notices.push_back(line); };
  SaliencyResult small = compute_saliency(m, o);
  CHECK(small.method == Method::Exact);
  CHECK(notices.empty());
  // A 24-eps ball over the whole mesh: every pair, n^2 > 2e9 for a 50k-vertex sphere.
  Mesh big = make_sphere(1.0, 7);
  REQUIRE(double(big.vertex_count()) * big.vertex_count() > kAutoPairBudget);
  o.eps_frac = 0.1;
  o.scales = {5};
  std::vector<uint8_t> is_point = referenced_vertices(big);
  const double pairs = estimate_sweep_pairs(big, is_point, 4 * 5 * scale_unit(big, is_point, 0.1));
  CHECK(pairs == Approx(double(big.vertex_count()) * big.vertex_count()).epsilon(1e-9));
  SaliencyResult large = compute_saliency(big, o);
  CHECK(large.method == Method::Fast);
  REQUIRE(notices.size() == 1);
  CHECK(notices[0].find("using the fast method") != std::string::npos);
  CHECK(notices[0].find("budget 2e+09") != std::string::npos);
}

TEST_CASE("pair estimate: within 10% of the exact sweep's count", "[fast]") {
  Mesh m = make_bumpy_sphere(5);
  std::vector<uint8_t> is_point = referenced_vertices(m);
  const double eps = scale_unit(m, is_point, 0.003);
  FilterStats stats;
  std::vector<double> values(m.vertex_count(), 1.0);
  gaussian_filter(m, is_point, values, {12 * eps}, 1, &stats);
  const double estimate = estimate_sweep_pairs(m, is_point, 24 * eps);
  INFO("estimate " << estimate << ", exact " << stats.pairs);
  CHECK(estimate == Approx(double(stats.pairs)).epsilon(0.1));
}

TEST_CASE("parse_method", "[fast]") {
  CHECK(parse_method("exact") == Method::Exact);
  CHECK(parse_method("fast") == Method::Fast);
  CHECK(parse_method("auto") == Method::Auto);
  CHECK_THROWS_WITH(parse_method("quick"), "method must be exact, fast or auto, got 'quick'");
}

TEST_CASE("fast filter: per-cell sums extrapolated to the vertices stay close to exact", "[fast]") {
  // Forces the per-cell path (which gaussian_filter_fast takes, per sigma, where that sigma's
  // non-empty cells hold at least FastFilterParams::points_per_query_cell = 2 points on
  // average, i.e. on dense scans) on a small mesh, and compares both paths with the exact sweep.
  // eps_frac 0.01 makes the cells hold ~10 points each.
  Mesh m = make_bumpy_sphere(5);
  std::vector<uint8_t> is_point = referenced_vertices(m);
  SaliencyOptions o;
  o.eps_frac = 0.01;
  SaliencyResult s = compute_saliency_cpu(m, o);
  const std::vector<double> sigmas{2 * s.eps, 6 * s.eps};
  auto exact = gaussian_filter(m, is_point, s.curvature, sigmas);
  FastFilterParams per_cell, per_vertex;
  per_cell.points_per_query_cell = 0;
  per_vertex.points_per_query_cell = INFINITY;
  auto a = gaussian_filter_fast(m, is_point, s.curvature, sigmas, 0, nullptr, {}, per_cell);
  auto b = gaussian_filter_fast(m, is_point, s.curvature, sigmas, 0, nullptr, {}, per_vertex);
  double hmax = 0;
  for (double h : s.curvature) hmax = std::max(hmax, std::fabs(h));
  double differ = 0;  // the two paths really differ (at 2 eps a cell holds at most one
                      // point: extrapolating by 0 there gives the per-vertex sums exactly)
  for (size_t k = 0; k < sigmas.size(); ++k) {
    double ea = 0, eb = 0;
    for (size_t v = 0; v < m.vertex_count(); ++v) {
      ea += std::fabs(a[k][v] - exact[k][v]) / hmax;
      eb += std::fabs(b[k][v] - exact[k][v]) / hmax;
      differ = std::max(differ, std::fabs(a[k][v] - b[k][v]));
    }
    ea /= m.vertex_count(), eb /= m.vertex_count();
    INFO("sigma " << sigmas[k] / s.eps << " eps: mean error per cell " << ea << ", per vertex " << eb);
    CHECK(ea < 0.01);
    CHECK(eb < 0.01);
  }
  CHECK(differ > 0);
}

TEST_CASE("fast filter: a tile's sigmas handed over one at a time equal the returned arrays", "[fast]") {
  // A tile's call (filter_scope.h): the queries a slab of the bumpy sphere, the frame its
  // whole box; with `take` each sigma's array goes to the caller as it is found (one held
  // at a time) and nothing is returned: the same bits at every query vertex.
  const Mesh m = make_bumpy_sphere(4);
  const size_t n = m.vertex_count();
  const std::vector<uint8_t> all(n, 1);
  std::vector<uint8_t> query(n, 0);
  for (size_t v = 0; v < n; ++v) query[v] = m.positions[3 * v + 2] > 0.3f ? 1 : 0;
  std::vector<double> values(n);
  for (size_t v = 0; v < n; ++v) values[v] = std::sin(7.0 * m.positions[3 * v]) + m.positions[3 * v + 1];
  const BoundingBox box = mesh_points_bbox(m, all);
  const double d = box.diagonal();
  const std::vector<double> sigmas = {0.006 * d, 0.009 * d, 0.012 * d, 0.024 * d, 0.036 * d};
  FilterScope scope;
  scope.frame = GridFrame{box, uint64_t(n)};
  scope.query = &query;
  scope.occupied_cells = count_fast_cells(m, all, all, box, sigmas);
  FilterStats returned_stats, handed_stats;
  const std::vector<std::vector<double>> returned =
      gaussian_filter_fast(m, all, values, sigmas, 2, &returned_stats, {}, {}, &scope);
  std::vector<std::vector<double>> handed(sigmas.size());
  std::vector<size_t> order;
  scope.take = [&](size_t k, const std::vector<double>& at) {
    order.push_back(k);
    for (size_t v = 0; v < n; ++v)
      if (query[v]) handed[k].push_back(at[v]);
  };
  CHECK(gaussian_filter_fast(m, all, values, sigmas, 2, &handed_stats, {}, {}, &scope).empty());
  CHECK(order == std::vector<size_t>{0, 1, 2, 3, 4});
  CHECK(handed_stats.pairs == returned_stats.pairs);
  for (size_t k = 0; k < sigmas.size(); ++k) {
    std::vector<double> expect;
    for (size_t v = 0; v < n; ++v)
      if (query[v]) expect.push_back(returned[k][v]);
    INFO("sigma " << k);
    CHECK(handed[k] == expect);
    CHECK(std::any_of(expect.begin(), expect.end(), [](double x) { return x != 0; }));
  }
}
