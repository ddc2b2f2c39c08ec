// The pieces of the fast method's CPU pipeline (saliency_fast_cpu.cpp), each against the
// path it replaces: curvature and suppression from the triangles against the 1-rings, the
// Morton renumbering against the input, the parallel radix sort against std::stable_sort,
// order statistics against a sort, and the pipeline itself with and without its raw maps.
#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <random>

#include "cli/synthetic.h"
#include "core/adjacency.h"
#include "core/kth_smallest.h"
#include "core/mesh_points.h"
#include "core/morton_order.h"
#include "core/peak_memory.h"
#include "core/radix_sort.h"
#include "saliency/curvature.h"
#include "saliency/saliency.h"
#include "saliency/suppression.h"
#include "test_util.h"

using namespace meshsal;

namespace {

// A bumpy sphere of 163,842 vertices (more than 2 x 64K, so that 2 and 4 threads split the
// vertices) with an unreferenced vertex and a degenerate triangle added.
Mesh test_mesh() {
  Mesh m = make_bumpy_sphere(7);
  m.positions.insert(m.positions.end(), {3.f, 3.f, 3.f});
  m.triangles.insert(m.triangles.end(), {5, 5, 9});
  return m;
}

}  // namespace

TEST_CASE("fast pipeline: curvature from the triangles equals the 1-ring curvature to rounding", "[fast]") {
  const Mesh m = test_mesh();
  const std::vector<double> normals = vertex_normals(m, 1);
  const std::vector<double> ring = mean_curvature(m, build_adjacency(m), normals);
  const std::vector<double> faces = mean_curvature_faces(m, normals, 1);
  REQUIRE(faces.size() == ring.size());
  double top = 0, worst = 0;
  for (double h : ring) top = std::max(top, std::fabs(h));
  for (size_t v = 0; v < ring.size(); ++v) worst = std::max(worst, std::fabs(faces[v] - ring[v]));
  INFO("worst " << worst << " of " << top);
  CHECK(top > 1.0);
  CHECK(worst <= 1e-12 * top);
  CHECK(faces.back() == 0.0);  // the unreferenced vertex
  // The same bits on any thread count (each vertex summed in triangle order).
  CHECK(vertex_normals(m, 4) == normals);
  CHECK(mean_curvature_faces(m, normals, 4) == faces);
  CHECK(mean_curvature_faces(m, vertex_normals(m, 3), 3) == faces);
}

TEST_CASE("fast pipeline: suppression from the triangles equals the 1-ring suppression bit for bit", "[fast]") {
  const Mesh m = test_mesh();
  const Adjacency adj = build_adjacency(m);
  const std::vector<uint8_t> is_point = referenced_vertices(m);
  std::mt19937 rng(3);
  std::uniform_int_distribution<int> level(0, 40);  // few levels: many ties between neighbours
  std::vector<double> map(m.vertex_count());
  for (double& x : map) x = level(rng) / 8.0;
  for (unsigned threads : {1u, 4u}) {
    SuppressionInfo a, b;
    const std::vector<double> ring = suppress(map, is_point, adj, &a);
    const std::vector<double> faces = suppress_faces(map, is_point, m, threads, &b);
    CHECK(faces == ring);
    std::vector<double> moved = map;  // normalised where it lies: the same bits
    CHECK(suppress_faces(std::move(moved), is_point, m, threads) == faces);
    CHECK(a.max == b.max);
    CHECK(a.mbar == b.mbar);
    CHECK(a.local_maxima == b.local_maxima);
    CHECK(a.local_maxima > 10);
  }
  // Neighbours a few double ulps apart, equal once rounded to float (where the triangle
  // pass falls back on the doubles), and exact ties: the same maxima as the 1-ring.
  std::vector<double> close(m.vertex_count());
  for (double& x : close) x = 1.0 + level(rng) * 0x1p-52;
  size_t float_ties = 0;
  for (size_t f = 0; f < m.triangle_count(); ++f) {
    const uint32_t a = m.triangles[3 * f], b = m.triangles[3 * f + 1];
    float_ties += close[a] != close[b] && float(close[a]) == float(close[b]);
  }
  CHECK(float_ties > 100);
  SuppressionInfo a, b;
  CHECK(suppress_faces(close, is_point, m, 2, &b) == suppress(close, is_point, adj, &a));
  CHECK(a.local_maxima == b.local_maxima);
  CHECK(a.local_maxima > 10);
  // A zero map stays zero.
  const std::vector<double> zero(m.vertex_count(), 0.0);
  CHECK(suppress_faces(zero, is_point, m) == zero);
}

TEST_CASE("fast pipeline: the Morton curvature's ranges give the same bits however many", "[fast]") {
  // 600k vertices: 8 ranges on one thread, 9 on two, 16+ on four (each range visits its own
  // block of the sorted triangles and the crossing ones): every partition the same bits,
  // and the curvature from the triangles in input order to rounding.
  Mesh m = make_plane_with_bump(2.0, 774, 0.3, 0.2);
  for (size_t v = 0; v < m.vertex_count(); ++v)
    m.positions[3 * v + 2] += 0.01f * float(std::sin(40.0 * m.positions[3 * v]) * std::cos(30.0 * m.positions[3 * v + 1]));
  REQUIRE(m.vertex_count() > 9 * 65536);
  const BoundingBox box = mesh_points_bbox(m, referenced_vertices(m));
  const std::vector<double> one = mean_curvature_morton(m, box, 1);
  CHECK(mean_curvature_morton(m, box, 2) == one);
  CHECK(mean_curvature_morton(m, box, 4) == one);
  const std::vector<double> faces = mean_curvature_faces(m, vertex_normals(m, 2), 2);
  double top = 0, worst = 0;
  for (size_t v = 0; v < faces.size(); ++v)
    top = std::max(top, std::fabs(faces[v])), worst = std::max(worst, std::fabs(one[v] - faces[v]));
  INFO("worst " << worst << " of " << top);
  CHECK(top > 1.0);
  CHECK(worst <= 1e-9 * top);
}

TEST_CASE("fast pipeline: the Morton renumbering keeps the surface", "[fast]") {
  for (uint32_t x : {0u, 1u, 5u, 0x155555u, 0x1fffffu}) {
    uint64_t naive = 0;
    for (int b = 0; b < 21; ++b) naive |= uint64_t((x >> b) & 1) << (3 * b);
    CHECK(spread_bits_21(x) == naive);
  }
  // The test mesh with its vertices shuffled, as a scan subdivided elsewhere may come.
  const Mesh base = test_mesh();
  std::vector<uint32_t> shuffle(base.vertex_count());
  for (size_t i = 0; i < shuffle.size(); ++i) shuffle[i] = uint32_t(i);
  std::shuffle(shuffle.begin(), shuffle.end(), std::mt19937(9));
  const Mesh m = renumbered_mesh(base, shuffle);
  const BoundingBox box = mesh_points_bbox(m, referenced_vertices(m));
  const MortonOrder curve = morton_order(m, box, 2);
  const std::vector<uint32_t>& order = curve.order;
  for (size_t i = 1; i < order.size(); ++i) REQUIRE(curve.code[i - 1] <= curve.code[i]);
  std::vector<uint32_t> sorted = order;
  std::sort(sorted.begin(), sorted.end());
  for (size_t i = 0; i < sorted.size(); ++i) REQUIRE(sorted[i] == i);  // a permutation
  CHECK(morton_order(m, box, 1).order == order);
  std::vector<uint32_t> new_of;
  std::vector<uint32_t> key(curve.code);
  for (uint32_t& k : key) k >>= 15;
  const Mesh w = renumbered_mesh(m, order, key, &new_of, 2);
  REQUIRE(w.vertex_count() == m.vertex_count());
  REQUIRE(w.triangle_count() == m.triangle_count());
  for (size_t i = 0; i < order.size(); ++i) {
    REQUIRE(new_of[order[i]] == i);
    for (int a = 0; a < 3; ++a) REQUIRE(w.positions[3 * i + a] == m.positions[3 * size_t(order[i]) + a]);
  }
  // The same triangles (as corner triples of input vertices), sorted by their corners'
  // smallest key.
  std::vector<std::array<uint32_t, 3>> in, out;
  uint32_t last_smallest = 0;
  bool faces_sorted = true;
  for (size_t f = 0; f < m.triangle_count(); ++f) {
    in.push_back({m.triangles[3 * f], m.triangles[3 * f + 1], m.triangles[3 * f + 2]});
    const uint32_t* t = &w.triangles[3 * f];
    out.push_back({order[t[0]], order[t[1]], order[t[2]]});
    const uint32_t smallest = std::min({key[t[0]], key[t[1]], key[t[2]]});
    faces_sorted &= smallest >= last_smallest;
    last_smallest = smallest;
  }
  CHECK(faces_sorted);
  // Stable: triangles of one smallest key keep their input order, with 16-bit keys (as
  // here) and wider ones (the 32-bit path).
  auto check_stable = [&](const std::vector<uint32_t>& keys) {
    const Mesh r = renumbered_mesh(m, order, keys, nullptr, 2);
    std::map<std::array<uint32_t, 3>, size_t> input_index;
    for (size_t f = 0; f < m.triangle_count(); ++f)
      input_index[{m.triangles[3 * f], m.triangles[3 * f + 1], m.triangles[3 * f + 2]}] = f;
    bool stable = true;
    uint32_t last_key = 0;
    size_t last_input = 0;
    for (size_t f = 0; f < r.triangle_count(); ++f) {
      const uint32_t* t = &r.triangles[3 * f];
      const size_t at = input_index.at({order[t[0]], order[t[1]], order[t[2]]});
      const uint32_t k = std::min({keys[t[0]], keys[t[1]], keys[t[2]]});
      if (f > 0) stable &= k > last_key || (k == last_key && at > last_input);
      last_key = k, last_input = at;
    }
    return stable;
  };
  CHECK(check_stable(key));
  std::vector<uint32_t> wide(curve.code);
  for (uint32_t& k : wide) k >>= 6;  // 24 bits
  CHECK(*std::max_element(wide.begin(), wide.end()) >= (1u << 16));
  CHECK(check_stable(wide));
  std::sort(in.begin(), in.end());
  std::sort(out.begin(), out.end());
  CHECK(in == out);
  // Neighbours along the curve are near in space: the mean distance between consecutive
  // vertices is a small fraction of the input order's.
  auto mean_step = [&](const std::vector<float>& p) {
    double sum = 0;
    for (size_t i = 1; i + 1 < m.vertex_count(); ++i) {
      double d2 = 0;
      for (int a = 0; a < 3; ++a) d2 += (p[3 * i + a] - p[3 * i - 3 + a]) * (p[3 * i + a] - p[3 * i - 3 + a]);
      sum += std::sqrt(d2);
    }
    return sum / double(m.vertex_count());
  };
  CHECK(mean_step(w.positions) < 0.1 * mean_step(m.positions));
  // The curvature through the renumbering is the input order's to rounding, and a tile
  // (here: the vertices with x < 0.3 and the triangles among them) gets the same bits at
  // every vertex whose triangles it holds all of, with the same box.
  const std::vector<double> H = mean_curvature_morton(m, box, 2);
  const std::vector<double> plain = mean_curvature_faces(m, vertex_normals(m));
  double top = 0, worst = 0;
  for (size_t v = 0; v < H.size(); ++v) {
    top = std::max(top, std::fabs(plain[v]));
    worst = std::max(worst, std::fabs(H[v] - plain[v]));
  }
  CHECK(worst <= 1e-12 * top);
  std::vector<uint32_t> keep;  // old -> tile index, UINT32_MAX where left out
  Mesh tile;
  std::vector<uint32_t> tile_of(m.vertex_count(), UINT32_MAX);
  for (size_t v = 0; v < m.vertex_count(); ++v)
    if (m.positions[3 * v] < 0.3f) {
      tile_of[v] = uint32_t(keep.size());
      keep.push_back(uint32_t(v));
      tile.positions.insert(tile.positions.end(), &m.positions[3 * v], &m.positions[3 * v + 3]);
    }
  std::vector<uint8_t> whole_ring(m.vertex_count(), 1);  // every triangle of v is in the tile
  for (size_t f = 0; f < m.triangle_count(); ++f) {
    const uint32_t* t = &m.triangles[3 * f];
    const bool in_tile = tile_of[t[0]] != UINT32_MAX && tile_of[t[1]] != UINT32_MAX && tile_of[t[2]] != UINT32_MAX;
    if (in_tile)
      tile.triangles.insert(tile.triangles.end(), {tile_of[t[0]], tile_of[t[1]], tile_of[t[2]]});
    else
      for (int c = 0; c < 3; ++c) whole_ring[t[c]] = 0;
  }
  const std::vector<double> H_tile = mean_curvature_morton(tile, box, 2);
  size_t compared = 0;
  bool same = true;
  for (size_t i = 0; i < keep.size(); ++i)
    if (whole_ring[keep[i]]) same &= H_tile[i] == H[keep[i]], compared++;
  CHECK(same);
  CHECK(compared > 10000);
}

TEST_CASE("fast pipeline: the parallel radix sort equals std::stable_sort", "[fast]") {
  std::mt19937_64 rng(11);
  for (uint64_t max_key : {uint64_t(0), uint64_t(1000), uint64_t(1) << 31, (uint64_t(1) << 45) + 17}) {
    const size_t n = 300000;
    std::vector<uint64_t> key(n);
    for (uint64_t& k : key) k = max_key ? rng() % (max_key + 1) : 0;
    std::vector<std::pair<uint64_t, uint32_t>> oracle;
    for (size_t i = 0; i < n; ++i) oracle.push_back({key[i], uint32_t(i)});
    std::stable_sort(oracle.begin(), oracle.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    for (unsigned threads : {1u, 3u}) {
      INFO("max key " << max_key << ", threads " << threads);
      std::vector<uint64_t> k64 = key;
      std::vector<uint32_t> v64(n);
      for (size_t i = 0; i < n; ++i) v64[i] = uint32_t(i);
      radix_sort(k64, v64, max_key, threads);
      bool same = true;
      for (size_t i = 0; i < n; ++i) same &= k64[i] == oracle[i].first && v64[i] == oracle[i].second;
      CHECK(same);
      if (max_key < (uint64_t(1) << 32)) {
        std::vector<uint32_t> k32(key.begin(), key.end()), v32(n);
        for (size_t i = 0; i < n; ++i) v32[i] = uint32_t(i);
        radix_sort(k32, v32, max_key, threads);
        bool same32 = true;
        for (size_t i = 0; i < n; ++i) same32 &= k32[i] == oracle[i].first && v32[i] == oracle[i].second;
        CHECK(same32);
      }
    }
  }
}

TEST_CASE("fast pipeline: the radix sort's top-digit buckets, skewed or single", "[fast]") {
  // Keys of 30 bits go top digit first, then each bucket by its low digits: keys crowded
  // into a few buckets (a surface in few z slabs), a single bucket, and buckets of one key.
  std::mt19937_64 rng(12);
  const uint64_t max_key = (uint64_t(1) << 30) - 1;
  for (int layout = 0; layout < 3; ++layout) {
    const size_t n = 200000;
    std::vector<uint32_t> key(n);
    for (uint32_t& k : key) {
      if (layout == 0) k = uint32_t((rng() % 3) << 27 | (rng() % 5000));  // 3 buckets
      if (layout == 1) k = uint32_t(12345u | (rng() % 2) << 3);             // 1 bucket, 2 keys
      if (layout == 2) k = uint32_t(rng() % (max_key + 1));                 // spread thin
    }
    std::vector<std::pair<uint32_t, uint32_t>> oracle;
    for (size_t i = 0; i < n; ++i) oracle.push_back({key[i], uint32_t(i)});
    std::stable_sort(oracle.begin(), oracle.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    for (unsigned threads : {1u, 2u}) {
      INFO("layout " << layout << ", threads " << threads);
      std::vector<uint32_t> k = key, v(n);
      for (size_t i = 0; i < n; ++i) v[i] = uint32_t(i);
      radix_sort(k, v, max_key, threads);
      bool same = true;
      for (size_t i = 0; i < n; ++i) same &= k[i] == oracle[i].first && v[i] == oracle[i].second;
      CHECK(same);
    }
  }
}

TEST_CASE("fast pipeline: order statistics equal a sort's", "[fast]") {
  std::mt19937 rng(5);
  std::vector<double> values(10001);
  for (double& x : values) x = double(rng() % 500) / 7.0;  // many repeats
  std::vector<double> sorted = values;
  std::sort(sorted.begin(), sorted.end());
  const std::vector<size_t> ks = {9000, 0, 5000, 5000, 10000, 1, 9999};
  std::vector<double> work = values;
  const std::vector<double> got = kth_smallest(work, ks);
  for (size_t i = 0; i < ks.size(); ++i) CHECK(got[i] == sorted[ks[i]]);
  CHECK_THROWS_AS(kth_smallest(work, {10001}), Error);
}

TEST_CASE("fast pipeline: order statistics of many values (the bucketed path) equal a sort's", "[fast]") {
  // Over 2^18 values, so the buckets of leading bits are used: negatives, both zeros, a
  // bucket holding a third of the values, values spread over many exponents.
  std::mt19937 rng(11);
  std::vector<double> values(700001);
  for (size_t i = 0; i < values.size(); ++i) {
    const uint32_t r = rng();
    if (i % 3 == 0) values[i] = 1.0 + double(r % 1000) * 1e-9;  // one crowded bucket
    else if (i % 7 == 0) values[i] = (r & 1) ? 0.0 : -0.0;
    else values[i] = (r & 2 ? -1.0 : 1.0) * std::ldexp(double(r % 100000) + 1.0, int(r % 40) - 20);
  }
  std::vector<double> sorted = values;
  std::sort(sorted.begin(), sorted.end());
  const size_t n = values.size();
  const std::vector<size_t> ks = {n - 1, 0, n / 2, n / 3, n / 3 + 1, n / 10, n / 10, 99 * n / 100, n / 7, 1};
  std::vector<double> work = values;
  const std::vector<double> got = kth_smallest(work, ks);
  for (size_t i = 0; i < ks.size(); ++i) CHECK(got[i] == sorted[ks[i]]);
  // Every value equal: one bucket holds them all.
  std::vector<double> same(300000, 2.5);
  CHECK(kth_smallest(same, {0, 150000, 299999}) == std::vector<double>{2.5, 2.5, 2.5});
  CHECK_THROWS_AS(kth_smallest(work, {n}), Error);
  // Zeros of both signs: +0 on the serial path and the bucketed one alike.
  for (const size_t count : {size_t(1000), size_t(300000)}) {
    std::vector<double> zeros(count);
    for (size_t i = 0; i < count; ++i) zeros[i] = i % 3 == 0 ? 1.0 : (i % 2 ? -0.0 : 0.0);
    const std::vector<double> z = kth_smallest(zeros, {0, count / 4, count / 2});
    for (double x : z) CHECK((x == 0 && !std::signbit(x)));
  }
}

TEST_CASE("fast pipeline: the scale order follows the chains k, 2k", "[fast]") {
  CHECK(fast_scale_order({2, 3, 4, 5, 6}) == std::vector<size_t>{0, 2, 1, 4, 3});
  CHECK(fast_scale_order({6, 5, 4, 3, 2}) == std::vector<size_t>{4, 2, 3, 0, 1});
  CHECK(fast_scale_order({1.5, 3}) == std::vector<size_t>{0, 1});
  CHECK(fast_scale_order({7}) == std::vector<size_t>{0});
}

TEST_CASE("fast pipeline: S is the same bits without the raw maps, and on any thread count", "[fast]") {
  const Mesh m = make_bumpy_sphere(5);
  SaliencyOptions o;
  o.backend = Backend::Cpu;
  o.method = Method::Fast;
  o.threads = 1;
  const SaliencyResult with = compute_saliency(m, o);
  REQUIRE(with.raw.size() == 5);
  o.raw_maps = false;
  o.threads = 3;
  const SaliencyResult without = compute_saliency(m, o);
  CHECK(without.raw.empty());
  CHECK(without.saliency == with.saliency);
  CHECK(without.curvature == with.curvature);
  CHECK(without.pairs == with.pairs);
  // Each raw map is |G(k) - G(2k)| of that scale, in the scales' order, whatever order
  // the pipeline ran them in: the exact path's maps are close to it at every scale.
  o.method = Method::Exact;
  o.raw_maps = true;
  const SaliencyResult exact = compute_saliency(m, o);
  for (size_t i = 0; i < 5; ++i) {
    double top = 0, err = 0;
    for (size_t v = 0; v < m.vertex_count(); ++v) {
      top = std::max(top, exact.raw[i][v]);
      err += std::fabs(with.raw[i][v] - exact.raw[i][v]);
    }
    INFO("scale " << i);
    CHECK(err / double(m.vertex_count()) < 0.01 * top);
  }
  // The exact path keeps no raw maps either when asked not to, and S does not change.
  o.raw_maps = false;
  const SaliencyResult exact_lean = compute_saliency(m, o);
  CHECK(exact_lean.raw.empty());
  CHECK(exact_lean.saliency == exact.saliency);
}

TEST_CASE("peak memory: a stage's mark restarts, the process's peak does not", "[fast]") {
  const uint64_t before = peak_resident_bytes();
  if (before == 0) {
    meshsal_test::skip_case("no /proc/self/status here");
    return;
  }
  {
    std::vector<char> big(size_t(200) << 20, 1);  // 200 MB touched
    CHECK(stage_peak_resident_bytes() >= big.size());
  }
  const uint64_t high = peak_resident_bytes();
  CHECK(high >= (uint64_t(200) << 20));
  if (!restart_peak_resident()) {
    meshsal_test::skip_case("the kernel's high-water mark cannot be restarted here");
    return;
  }
  // The 200 MB were freed before the restart (under AddressSanitizer its quarantine keeps
  // freed blocks resident: tools/sanitize.sh saw the mark 20 KB above the old peak).
  if (!meshsal_test::kAddressSanitizer) CHECK(stage_peak_resident_bytes() < high);
  CHECK(peak_resident_bytes() >= high);        // but the process's peak remembers them
}
