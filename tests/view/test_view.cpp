// Viewpoint selection: camera, CPU visibility twin, optimiser vs exhaustive map (SPEC 3).
#include <cmath>
#include <numeric>

#include "view/camera.h"
#include "meshsal/meshsal.h"
#include "saliency/saliency.h"
#include "cli/synthetic.h"
#include "view/viewpoint.h"
#include "view/visibility.h"
#include "test_util.h"

using namespace meshsal;

namespace {
const double kPi = 3.14159265358979323846;

ViewScorer cpu_scorer(const Mesh& mesh, const std::vector<float>& w, const VisibilityOptions& o) {
  ViewFrame frame = frame_mesh(mesh);
  return [&mesh, &w, frame, o](const std::vector<ViewAngles>& v) { return visible_score_cpu(mesh, w, frame, v, o); };
}
}  // namespace

TEST_CASE("camera: direction formula, angles round trip and an orthonormal basis", "[view]") {
  double d[3];
  view_direction({0, 0}, d);
  CHECK(d[2] == Approx(1));
  view_direction({kPi / 2, 0}, d);
  CHECK(d[0] == Approx(1));
  view_direction({0, kPi / 2}, d);
  CHECK(d[1] == Approx(1));
  for (double th : {-3.0, -1.0, 0.0, 0.7, 2.5})
    for (double ph : {-1.5, -0.3, 0.0, 0.9, 1.5}) {
      ViewAngles a{th, ph};
      double r[3], u[3], dd[3];
      view_basis(a, r, u, dd);
      auto dot = [](const double* x, const double* y) { return x[0] * y[0] + x[1] * y[1] + x[2] * y[2]; };
      CHECK(dot(r, r) == Approx(1));
      CHECK(dot(u, u) == Approx(1));
      CHECK(std::fabs(dot(r, u)) < 1e-12);
      CHECK(std::fabs(dot(r, dd)) < 1e-12);
      CHECK(std::fabs(dot(u, dd)) < 1e-12);
      CHECK(u[1] >= -1e-12);  // up never points down: the image is upright
      ViewAngles b = direction_angles(dd);
      CHECK(b.theta == Approx(th).margin(1e-9));
      CHECK(b.phi == Approx(ph).margin(1e-9));
    }
}

TEST_CASE("camera: projection frames the bounding sphere", "[view]") {
  ViewFrame f;
  f.centre[0] = 1;
  f.centre[1] = 2;
  f.centre[2] = 3;
  f.radius = 2;
  ViewRows v = view_rows(f, {0, 0});  // looks along -z from +z; right = +x, up = +y
  Projected c = project(v, 1, 2, 3, 50);
  CHECK(c.px == Approx(50));
  CHECK(c.py == Approx(50));
  CHECK(c.depth == Approx(0.5));
  Projected near = project(v, 1, 2, 5, 50);  // c + R d: nearest possible point
  CHECK(near.depth == Approx(0).margin(1e-6));
  Projected corner = project(v, 3, 4, 1, 50);  // right, top, far
  CHECK(corner.px == Approx(100));
  CHECK(corner.py == Approx(0).margin(1e-5));
  CHECK(corner.depth == Approx(1));
}

TEST_CASE("visibility: a sphere shows its front hemisphere", "[view]") {
  Mesh s = make_sphere(1.0, 4);
  ViewFrame frame = frame_mesh(s);
  VisibilityOptions o;
  o.resolution = 128;
  for (ViewAngles a : {ViewAngles{0, 0}, ViewAngles{1.3, 0.4}, ViewAngles{-2.0, -1.2}, ViewAngles{0.3, 1.5707}}) {
    double d[3];
    view_direction(a, d);
    std::vector<uint8_t> vis = visible_vertices_cpu(s, frame, a, o);
    size_t wrong = 0, shown = 0;
    for (size_t i = 0; i < s.vertex_count(); ++i) {
      double nd = (s.positions[3 * i] * d[0] + s.positions[3 * i + 1] * d[1] + s.positions[3 * i + 2] * d[2]);
      if (nd > 0.35 && !vis[i]) ++wrong;   // clearly facing the viewer
      if (nd < -0.05 && vis[i]) ++wrong;   // behind the sphere
      shown += vis[i];
    }
    CHECK(wrong == 0);
    double frac = double(shown) / double(s.vertex_count());
    CHECK(frac > 0.44);
    CHECK(frac < 0.53);
  }
  // The z-buffer at the image centre holds the sphere's front: depth (1 - r/R) / 2.
  std::vector<float> z = depth_buffer_cpu(s, view_rows(frame, {0.4, 0.2}), 128);
  float centre = z[64 * 128 + 64];
  CHECK(centre == Approx((1.0 - 1.0 / frame.radius) / 2).margin(0.01));
  CHECK(std::isinf(z[0]));  // corner: empty
}

TEST_CASE("visibility: visible_score_cpu sums the weights of visible_vertices_cpu", "[view]") {
  Mesh s = make_cube(6);
  std::vector<double> score(s.vertex_count());
  for (size_t i = 0; i < score.size(); ++i) score[i] = 1.0 + double(i % 7);
  std::vector<float> w = visibility_weights(s, score);
  ViewFrame frame = frame_mesh(s);
  VisibilityOptions o;
  o.resolution = 96;
  std::vector<ViewAngles> views = fibonacci_directions(12);
  std::vector<double> U = visible_score_cpu(s, w, frame, views, o);
  for (size_t v = 0; v < views.size(); ++v) {
    std::vector<uint8_t> vis = visible_vertices_cpu(s, frame, views[v], o);
    double sum = 0;
    for (size_t i = 0; i < vis.size(); ++i) sum += vis[i] ? score[i] : 0.0;
    CHECK(U[v] == Approx(sum));
    CHECK(sum > 0);
  }
  CHECK_THROWS_AS(visibility_weights(s, std::vector<double>(3, 1.0)), Error);
  o.resolution = 4;
  CHECK_THROWS_AS(visible_score_cpu(s, w, frame, views, o), Error);
}

TEST_CASE("viewpoint: Fibonacci directions cover the sphere evenly", "[view]") {
  std::vector<ViewAngles> v = fibonacci_directions(400);
  REQUIRE(v.size() == 400);
  std::vector<double> d(3 * v.size());
  double mean[3] = {0, 0, 0};
  for (size_t i = 0; i < v.size(); ++i) {
    view_direction(v[i], &d[3 * i]);
    for (int k = 0; k < 3; ++k) mean[k] += d[3 * i + k] / double(v.size());
  }
  CHECK(std::sqrt(mean[0] * mean[0] + mean[1] * mean[1] + mean[2] * mean[2]) < 0.01);
  // Every direction on the sphere has a map direction within ~1.2x the mean spacing.
  double spacing = std::sqrt(4 * kPi / 400.0), worst = 0;
  for (ViewAngles q : fibonacci_directions(3001)) {
    double p[3], best = -1;
    view_direction(q, p);
    for (size_t i = 0; i < v.size(); ++i)
      best = std::max(best, p[0] * d[3 * i] + p[1] * d[3 * i + 1] + p[2] * d[3 * i + 2]);
    worst = std::max(worst, std::acos(std::min(1.0, best)));
  }
  CHECK(worst < 1.2 * spacing);
  CHECK_THROWS_AS(fibonacci_directions(0), Error);
}

TEST_CASE("viewpoint: a cube with one salient patch is viewed from the patch's face", "[view]") {
  Mesh cube = make_cube(16);
  VisibilityOptions o;
  o.resolution = 96;
  // Faces +x, -y (from below: the pole of the parametrisation) and -z.
  const int axes[3] = {0, 1, 2};
  const double sides[3] = {1, -1, -1};
  for (int f = 0; f < 3; ++f) {
    int a = axes[f];
    std::vector<double> score(cube.vertex_count(), 0.001);
    std::vector<size_t> patch;
    for (size_t i = 0; i < cube.vertex_count(); ++i) {
      const float* p = &cube.positions[3 * i];
      bool on_face = std::fabs(p[a] - sides[f]) < 1e-6;
      bool central = std::fabs(p[(a + 1) % 3]) < 0.3 && std::fabs(p[(a + 2) % 3]) < 0.3;
      if (on_face && central) {
        score[i] = 1.0;
        patch.push_back(i);
      }
    }
    REQUIRE(patch.size() >= 9);
    std::vector<float> w = visibility_weights(cube, score);
    OptimiserOptions opt;
    opt.restarts = 4;
    opt.seed = 7;
    OptimiserResult r = optimise_viewpoint(cpu_scorer(cube, w, o), opt);
    double d[3];
    view_direction(r.best, d);
    INFO("face " << f << " best direction " << d[0] << " " << d[1] << " " << d[2]);
    CHECK(d[a] * sides[f] > 0.4);  // the face is seen, not at a grazing angle
    std::vector<uint8_t> vis = visible_vertices_cpu(cube, frame_mesh(cube), r.best, o);
    size_t seen = 0;
    for (size_t i : patch) seen += vis[i];
    CHECK(seen == patch.size());
    CHECK(r.U >= double(patch.size()));
    CHECK(r.views_evaluated > 4);
  }
}

TEST_CASE("viewpoint: the optimiser is seeded and repeats", "[view]") {
  Mesh s = make_bumpy_sphere(3);
  std::vector<double> score(s.vertex_count());
  for (size_t i = 0; i < score.size(); ++i) score[i] = std::max(0.0, double(s.positions[3 * i]));  // +x side
  std::vector<float> w = visibility_weights(s, score);
  VisibilityOptions o;
  o.resolution = 64;
  OptimiserOptions opt;
  opt.restarts = 3;
  OptimiserResult a = optimise_viewpoint(cpu_scorer(s, w, o), opt);
  OptimiserResult b = optimise_viewpoint(cpu_scorer(s, w, o), opt);
  CHECK(a.best.theta == b.best.theta);
  CHECK(a.best.phi == b.best.phi);
  CHECK(a.U == b.U);
  opt.seed = 2;
  OptimiserResult c = optimise_viewpoint(cpu_scorer(s, w, o), opt);
  CHECK(c.starts[0].theta != a.starts[0].theta);
  double d[3];
  view_direction(a.best, d);
  CHECK(d[0] > 0.9);  // the +x weighted side faces the viewer
}

TEST_CASE("viewpoint: gradient ascent reaches 98% of the exhaustive maximum on real meshes", "[view]") {
  for (const char* name : {"bunny_3k.off", "spot_3k.obj", "max_planck_5k.obj"}) {
    MESHSAL_MESH_OR_CONTINUE(path, name);
    Mesh mesh = load_mesh(path);
    SaliencyOptions so;
    std::vector<double> sal = compute_saliency_cpu(mesh, so).saliency;
    std::vector<float> w = visibility_weights(mesh, sal);
    VisibilityOptions o;
    o.resolution = 128;
    ViewScorer scorer = cpu_scorer(mesh, w, o);
    ViewMap map = exhaustive_map(scorer, 600);
    OptimiserResult r = optimise_viewpoint(scorer, OptimiserOptions{});
    double best_map = map.U[map.best];
    INFO(name << ": optimiser U " << r.U << " exhaustive " << best_map << " after " << r.views_evaluated << " views");
    CHECK(r.U >= 0.98 * best_map);
    CHECK(r.views_evaluated < 600);  // cheaper than the map
    // The best view sees a real share of all saliency, and clearly more than the worst view.
    double total = std::accumulate(w.begin(), w.end(), 0.0);
    double worst_map = *std::min_element(map.U.begin(), map.U.end());
    CHECK(r.U > 0.3 * total);
    CHECK(r.U < total);
    CHECK(best_map > 1.1 * worst_map);
  }
}
