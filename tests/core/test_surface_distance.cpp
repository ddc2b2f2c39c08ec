// Surface distances: point-to-triangle cases, the BVH against brute force, Hausdorff / RMS on
// shapes with known answers, and the salient-region error.
#include <cmath>
#include <random>

#include "meshsal/meshsal.h"
#include "core/surface_distance.h"
#include "cli/synthetic.h"
#include "test_util.h"

using namespace meshsal;

TEST_CASE("point-triangle distance: face, edge and vertex regions", "[simplify]") {
  const double a[3] = {0, 0, 0}, b[3] = {1, 0, 0}, c[3] = {0, 1, 0};
  const double above[3] = {0.2, 0.2, 0.5};
  CHECK(point_triangle_distance_sq(above, a, b, c) == Approx(0.25));
  const double past_edge[3] = {0.5, -2, 0};  // closest to the edge ab
  CHECK(point_triangle_distance_sq(past_edge, a, b, c) == Approx(4.0));
  const double past_hyp[3] = {1, 1, 0};      // closest to the middle of bc
  CHECK(point_triangle_distance_sq(past_hyp, a, b, c) == Approx(0.5));
  const double past_vertex[3] = {-1, -1, 1};  // closest to a
  CHECK(point_triangle_distance_sq(past_vertex, a, b, c) == Approx(3.0));
  const double beyond_b[3] = {3, -1, 0};
  CHECK(point_triangle_distance_sq(beyond_b, a, b, c) == Approx(5.0));
  // A degenerate (collinear) triangle is its segment.
  const double d[3] = {2, 0, 0};
  const double p[3] = {1.5, 1, 0};
  CHECK(point_triangle_distance_sq(p, a, b, d) == Approx(1.0));
  CHECK(point_triangle_distance_sq(p, a, a, a) == Approx(1.5 * 1.5 + 1));
}

TEST_CASE("point-triangle distance agrees with dense sampling of random triangles", "[simplify]") {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int trial = 0; trial < 200; ++trial) {
    double t[3][3], p[3];
    for (auto& v : t)
      for (double& x : v) x = u(rng);
    for (double& x : p) x = 2 * u(rng);
    const double d = std::sqrt(point_triangle_distance_sq(p, t[0], t[1], t[2]));
    double best = HUGE_VAL;
    const int n = 200;
    for (int i = 0; i <= n; ++i)
      for (int j = 0; i + j <= n; ++j) {
        const double s = double(i) / n, r = double(j) / n;
        double q[3], dd = 0;
        for (int k = 0; k < 3; ++k) {
          q[k] = t[0][k] + s * (t[1][k] - t[0][k]) + r * (t[2][k] - t[0][k]);
          dd += (q[k] - p[k]) * (q[k] - p[k]);
        }
        best = std::min(best, std::sqrt(dd));
      }
    INFO("trial " << trial);
    CHECK(d <= best + 1e-12);      // never above any point of the triangle
    CHECK(d >= best - 0.02);       // and as close as the sampling resolution allows
  }
}

TEST_CASE("BVH closest distance equals brute force", "[simplify]") {
  MESHSAL_REQUIRE_MESH(path, "bunny_3k.off");
  const Mesh m = load_mesh(path);
  const TriangleBvh bvh = build_triangle_bvh(m);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-0.15, 0.25);
  for (int i = 0; i < 500; ++i) {
    const double p[3] = {u(rng) - 0.05, u(rng), u(rng) - 0.05};
    REQUIRE(surface_distance(bvh, p) == surface_distance_bruteforce(m, p));
  }
  // Points on the surface are at distance 0.
  for (size_t v = 0; v < m.vertex_count(); v += 97) {
    const double p[3] = {m.positions[3 * v], m.positions[3 * v + 1], m.positions[3 * v + 2]};
    CHECK(surface_distance(bvh, p) == 0.0);
  }
}

TEST_CASE("compare: identical surfaces, offset planes, salient error", "[simplify]") {
  const Mesh plane = make_plane(2.0, 8);
  SurfaceComparison r = compare_surfaces(plane, plane, {});
  CHECK(r.hausdorff < 1e-6);  // rounding of the area samples only
  CHECK(r.rms < 1e-6);
  CHECK(r.salient_error == -1.0);
  CHECK(r.forward_samples == plane.vertex_count() + 200000);

  // The same square lifted by 0.25 and coarser: every distance is exactly 0.25.
  Mesh lifted = make_plane(2.0, 3);
  for (size_t v = 0; v < lifted.vertex_count(); ++v) lifted.positions[3 * v + 2] = 0.25f;
  r = compare_surfaces(plane, lifted, {});
  CHECK(r.hausdorff == Approx(0.25));
  CHECK(r.rms == Approx(0.25));
  CHECK(r.forward_max == Approx(0.25));
  CHECK(r.backward_max == Approx(0.25));
  CHECK(r.diagonal == Approx(std::sqrt(8.0)));

  // Sphere against a coarser inscribed icosphere: Hausdorff is the worst chordal gap, found
  // in the forward direction; RMS lies between 0 and it.
  const Mesh fine = make_sphere(1.0, 4), coarse = make_sphere(1.0, 1);
  r = compare_surfaces(fine, coarse, {});
  CHECK(r.hausdorff > 0.02);
  CHECK(r.hausdorff < 0.1);
  CHECK(r.forward_max >= r.backward_max);
  CHECK(r.rms > 0);
  CHECK(r.rms < r.hausdorff);

  // Salient error: the top 30% of the vertices (here by x) are each 0.25 from the lifted copy.
  std::vector<double> s(plane.vertex_count());
  for (size_t v = 0; v < s.size(); ++v) s[v] = plane.positions[3 * v];  // salient: large x
  r = compare_surfaces(plane, lifted, s);
  CHECK(r.salient_vertices == size_t(std::ceil(0.3 * plane.vertex_count())));
  CHECK(r.salient_error == Approx(0.25));
  const std::vector<double> wrong(3, 1.0);
  CHECK_THROWS_AS(compare_surfaces(plane, lifted, wrong), Error);
  CHECK_THROWS_AS(compare_surfaces(plane, Mesh{}, {}), Error);
}

TEST_CASE("salient error measures only the most salient vertices", "[simplify]") {
  // A bump plane against the flat plane: the bump vertices are far, the rest are on it.
  const Mesh bump = make_plane_with_bump(2.0, 20, 0.5, 0.2);
  const Mesh flat = make_plane(2.0, 4);
  const TriangleBvh bvh = build_triangle_bvh(flat);
  std::vector<double> height(bump.vertex_count()), flatness(bump.vertex_count());
  for (size_t v = 0; v < height.size(); ++v) {
    height[v] = bump.positions[3 * v + 2];
    flatness[v] = -height[v];
  }
  size_t n = 0;
  const double on_bump = salient_region_error(bump, height, bvh, 0.05, &n);
  const double off_bump = salient_region_error(bump, flatness, bvh, 0.30, &n);
  CHECK(n == size_t(std::ceil(0.3 * bump.vertex_count())));
  CHECK(on_bump > 0.3);
  CHECK(off_bump < 1e-3);
}

TEST_CASE("surface sampling covers the area in proportion", "[simplify]") {
  const Mesh plane = make_plane(2.0, 2);
  const std::vector<double> pts = sample_surface(plane, 10000);
  REQUIRE(pts.size() == 3 * (plane.vertex_count() + 10000));
  size_t left = 0;
  for (size_t i = plane.vertex_count(); i < pts.size() / 3; ++i) {
    CHECK(std::fabs(pts[3 * i]) <= 1.0);
    CHECK(std::fabs(pts[3 * i + 1]) <= 1.0);
    if (pts[3 * i] < 0) left++;
  }
  CHECK(double(left) / 10000 == Approx(0.5).margin(0.02));
}
