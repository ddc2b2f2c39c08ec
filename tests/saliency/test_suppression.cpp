// Itti suppression on hand-made maps over a path graph (SPEC 1, "Suppression").
#include "core/adjacency.h"
#include "saliency/suppression.h"
#include "test_util.h"

using namespace meshsal;

// A strip of triangles 0..n-1 whose 1-ring is a band: neighbours within index distance 2.
static Mesh strip(size_t n) {
  Mesh m;
  for (size_t i = 0; i < n; ++i) m.positions.insert(m.positions.end(), {float(i), float(i % 2), 0.f});
  for (uint32_t i = 0; i + 2 < n; ++i) m.triangles.insert(m.triangles.end(), {i, i + 1, i + 2});
  return m;
}

TEST_CASE("suppression normalises and damps by the mean of the other local maxima",
          "[suppression]") {
  Mesh m = strip(12);
  Adjacency adj = build_adjacency(m);
  std::vector<uint8_t> is_point(12, 1);
  // Local maxima (strictly above neighbours within distance 2): index 2 (4.0), 6 (2.0), 10 (1.0).
  std::vector<double> map = {0, 0.5, 4.0, 0.5, 0, 0.5, 2.0, 0.5, 0, 0.2, 1.0, 0.2};
  SuppressionInfo info;
  auto out = suppress(map, is_point, adj, &info);
  CHECK(info.max == 4.0);
  CHECK(info.local_maxima == 3);
  CHECK(info.mbar == Approx((0.5 + 0.25) / 2));
  const double f = (1 - 0.375) * (1 - 0.375);
  CHECK(out[2] == Approx(1.0 * f));
  CHECK(out[6] == Approx(0.5 * f));
  CHECK(out[1] == Approx(0.125 * f));
}

TEST_CASE("suppression: a zero map stays zero, a single peak is kept whole", "[suppression]") {
  Mesh m = strip(8);
  Adjacency adj = build_adjacency(m);
  std::vector<uint8_t> is_point(8, 1);
  auto zero = suppress(std::vector<double>(8, 0.0), is_point, adj);
  for (double x : zero) CHECK(x == 0.0);
  std::vector<double> one = {0, 0, 0, 3, 0, 0, 0, 0};
  SuppressionInfo info;
  auto out = suppress(one, is_point, adj, &info);
  CHECK(info.mbar == 0.0);
  CHECK(out[3] == 1.0);
}

TEST_CASE("suppression: plateaus are not local maxima", "[suppression]") {
  Mesh m = strip(8);
  Adjacency adj = build_adjacency(m);
  std::vector<uint8_t> is_point(8, 1);
  std::vector<double> map = {0, 0, 2, 2, 0, 0, 0, 1};
  SuppressionInfo info;
  suppress(map, is_point, adj, &info);
  CHECK(info.local_maxima == 1);  // only index 7; the tied pair 2,3 is no strict maximum
  CHECK(info.mbar == Approx(0.5));
}
