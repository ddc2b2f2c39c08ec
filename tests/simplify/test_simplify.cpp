// Simplification: exact face counts, topology kept, no flips, the heap against the
// brute-force oracle, bad input.
#include <cmath>
#include <random>

#include "meshsal/meshsal.h"
#include "simplify/simplify.h"
#include "cli/synthetic.h"
#include "test_simplify_util.h"
#include "test_util.h"

using namespace meshsal;
using simplify_test::topology;

static SimplifyOptions target(size_t faces) {
  SimplifyOptions o;
  o.target_faces = faces;
  return o;
}

TEST_CASE("simplify: exact face counts on a closed sphere", "[simplify]") {
  const Mesh sphere = make_sphere(1.0, 3);  // 1280 faces
  for (size_t n : {1278, 1000, 500, 100, 20, 4}) {
    const Simplified s = simplify_mesh(sphere, target(n));
    const Mesh& out = s.mesh;
    const SimplifyReport& rep = s.report;
    INFO("target " << n);
    CHECK(out.triangle_count() == n);
    CHECK(rep.reached);
    CHECK(rep.note.empty());
    CHECK(rep.collapses == (1280 - n) / 2);
    // Euler: a closed genus-0 mesh has V = F/2 + 2.
    CHECK(out.vertex_count() == n / 2 + 2);
  }
  // Same face count: nothing to do.
  CHECK(simplify_mesh(sphere, target(1280)).mesh.triangle_count() == 1280);
}

TEST_CASE("simplify: unreachable targets stop above them and say why", "[simplify]") {
  const Mesh sphere = make_sphere(1.0, 2);  // 320 faces, closed: only even counts
  Simplified s = simplify_mesh(sphere, target(101));
  CHECK(s.mesh.triangle_count() == 102);
  CHECK_FALSE(s.report.reached);
  CHECK(s.report.note.find("even") != std::string::npos);
  // Below the tetrahedron no collapse keeps a closed manifold.
  s = simplify_mesh(sphere, target(2));
  CHECK(s.mesh.triangle_count() == 4);
  CHECK_FALSE(s.report.reached);
  CHECK(s.report.note.find("stopped at 4") != std::string::npos);
}

TEST_CASE("simplify: open meshes reach odd targets and keep their border", "[simplify]") {
  const Mesh plane = make_plane_with_bump(2.0, 12, 0.3, 0.3);  // 288 faces, open
  const size_t border_before = topology(plane).border_edges;
  for (size_t n : {287, 201, 77}) {
    const Simplified s = simplify_mesh(plane, target(n));
    const Mesh& out = s.mesh;
    const SimplifyReport& rep = s.report;
    INFO("target " << n);
    CHECK(out.triangle_count() == n);
    CHECK(rep.reached);
    const auto t = topology(out);
    CHECK(t.nonmanifold_edges == 0);
    CHECK(t.repeated_directed == 0);
    CHECK(t.border_edges > 0);
    CHECK(t.border_edges <= border_before);
  }
  // The border of a flat square stays on the square: corners are kept by border quadrics.
  const Mesh flat = make_plane(2.0, 10);
  const Mesh out = simplify_mesh(flat, target(20)).mesh;
  float lo = 1e9f, hi = -1e9f;
  for (size_t v = 0; v < out.vertex_count(); ++v) {
    lo = std::min(lo, out.positions[3 * v]);
    hi = std::max(hi, out.positions[3 * v]);
    CHECK(out.positions[3 * v + 2] == 0.0f);
  }
  CHECK(lo == Approx(-1.0f));
  CHECK(hi == Approx(1.0f));
}

static void check_closed_result(const Mesh& in, const Mesh& out, double volume_tolerance) {
  const auto t = topology(out);
  CHECK(t.border_edges == 0);
  CHECK(t.nonmanifold_edges == 0);
  CHECK(t.repeated_directed == 0);
  CHECK(t.nonmanifold_vertices == 0);
  CHECK(t.repeated_index == 0);
  CHECK(t.unreferenced == 0);
  CHECK(simplify_test::min_shape_ratio(out) > 1e-6);
  const double v0 = simplify_test::signed_volume(in), v1 = simplify_test::signed_volume(out);
  INFO("volume " << v0 << " -> " << v1);
  CHECK(v1 > 0);
  CHECK(std::fabs(v1 - v0) < volume_tolerance * std::fabs(v0));
}

TEST_CASE("simplify: closed manifold inputs stay closed, manifold and oriented", "[simplify]") {
  for (const char* name : {"bunny_3k.off", "spot_3k.obj"}) {
    MESHSAL_MESH_OR_CONTINUE(path, name);
    const Mesh in = load_mesh(path);
    REQUIRE(topology(in).border_edges == 0);
    for (double ratio : {0.5, 0.1, 0.02}) {
      SimplifyOptions o;
      o.ratio = ratio;
      const Simplified s = simplify_mesh(in, o);
      const Mesh& out = s.mesh;
      const SimplifyReport& rep = s.report;
      INFO(name << " ratio " << ratio);
      CHECK(rep.target_faces == size_t(std::llround(ratio * in.triangle_count())));
      // A closed manifold mesh only has even face counts: odd targets end one above.
      if (rep.target_faces % 2 == 0) {
        CHECK(rep.reached);
        CHECK(out.triangle_count() == rep.target_faces);
      } else {
        CHECK_FALSE(rep.reached);
        CHECK(out.triangle_count() == rep.target_faces + 1);
        CHECK(rep.note.find("even face count") != std::string::npos);
      }
      check_closed_result(in, out, ratio < 0.05 ? 0.1 : 0.02);
    }
  }
}

TEST_CASE("simplify: no flipped or degenerate triangles on a sphere", "[simplify]") {
  const Mesh sphere = make_sphere(2.0, 4);  // 5120 faces
  for (size_t n : {2000, 200, 40}) {
    const Mesh out = simplify_mesh(sphere, target(n)).mesh;
    INFO("target " << n);
    REQUIRE(out.triangle_count() == n);
    check_closed_result(sphere, out, n >= 200 ? 0.05 : 0.35);
    // Every face of a convex, origin-centred result faces outwards.
    size_t inward = 0;
    for (size_t t = 0; t < out.triangle_count(); ++t) {
      double nrm[3], c[3];
      simplify_test::triangle_normal(out, t, nrm, c);
      if (nrm[0] * c[0] + nrm[1] * c[1] + nrm[2] * c[2] <= 0) inward++;
    }
    CHECK(inward == 0);
    // And every vertex stays close to the sphere.
    for (size_t v = 0; v < out.vertex_count(); ++v) {
      const double r = std::sqrt(double(out.positions[3 * v]) * out.positions[3 * v] +
                                 double(out.positions[3 * v + 1]) * out.positions[3 * v + 1] +
                                 double(out.positions[3 * v + 2]) * out.positions[3 * v + 2]);
      CHECK(r == Approx(2.0).epsilon(0.12));
    }
  }
}

static void check_same_sequence(const Mesh& mesh, size_t faces, const std::vector<double>* w) {
  SimplifyOptions o = target(faces);
  o.record_collapses = true;
  const Simplified s = simplify_mesh(mesh, o, w ? *w : std::vector<double>{});
  const Mesh& a = s.mesh;
  const SimplifyReport& fast = s.report;
  SimplifyReport brute;
  const Mesh b = simplify_bruteforce(mesh, o, w, &brute);
  REQUIRE(fast.sequence.size() == brute.sequence.size());
  REQUIRE(fast.sequence.size() > 0);
  size_t first_difference = fast.sequence.size();
  for (size_t i = 0; i < fast.sequence.size(); ++i) {
    const Collapse& x = fast.sequence[i];
    const Collapse& y = brute.sequence[i];
    if (x.kept != y.kept || x.removed != y.removed || x.cost != y.cost) {
      first_difference = i;
      break;
    }
  }
  CHECK(first_difference == fast.sequence.size());
  CHECK(a.triangles == b.triangles);
  CHECK(a.positions == b.positions);
  for (const Collapse& c : fast.sequence) CHECK(c.kept != c.removed);
}

TEST_CASE("simplify: the heap picks the same collapses as the brute-force recomputation",
          "[simplify]") {
  SECTION("sphere") { check_same_sequence(make_sphere(1.0, 2), 40, nullptr); }
  SECTION("open plane with a bump (borders)") {
    check_same_sequence(make_plane_with_bump(2.0, 10, 0.4, 0.3), 21, nullptr);
  }
  SECTION("bumpy sphere") { check_same_sequence(make_bumpy_sphere(2), 60, nullptr); }
  SECTION("random weights") {
    const Mesh m = make_bumpy_sphere(2);
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(0.0, 100.0);
    std::vector<double> w(m.vertex_count());
    for (double& x : w) x = u(rng);
    check_same_sequence(m, 50, &w);
  }
  SECTION("bunny_3k") {
    MESHSAL_REQUIRE_MESH(path, "bunny_3k.off");
    check_same_sequence(load_mesh(path), 5600, nullptr);
  }
}

TEST_CASE("simplify: weights steer the collapses away from weighted vertices", "[simplify]") {
  // Heavy weights on one half of a bumpy sphere keep more vertices there.
  const Mesh m = make_bumpy_sphere(3);
  std::vector<double> w(m.vertex_count(), 1.0);
  for (size_t v = 0; v < w.size(); ++v)
    if (m.positions[3 * v + 2] > 0) w[v] = 1000.0;
  const Simplified s = simplify_mesh(m, target(400), w);
  const Mesh& out = s.mesh;
  const SimplifyReport& rep = s.report;
  REQUIRE(out.triangle_count() == 400);
  size_t upper = 0;
  for (size_t v = 0; v < out.vertex_count(); ++v)
    if (out.positions[3 * v + 2] > 0) upper++;
  INFO(upper << " of " << out.vertex_count() << " vertices in the heavy half");
  CHECK(upper > 0.7 * out.vertex_count());
  // vertex_origin points back to input vertices.
  REQUIRE(rep.vertex_origin.size() == out.vertex_count());
  for (size_t v = 1; v < rep.vertex_origin.size(); ++v)
    CHECK(rep.vertex_origin[v] > rep.vertex_origin[v - 1]);
}

TEST_CASE("simplify: bad input is refused with a clear error", "[simplify]") {
  const Mesh sphere = make_sphere(1.0, 1);  // 80 faces
  // (A target above the face count is no error: the mesh comes back unchanged, see
  // test_simplify_whole_mesh.cpp.)
  CHECK_THROWS_WITH(simplify_mesh(sphere, SimplifyOptions{}).mesh, Catch::Contains("target face count"));
  SimplifyOptions r;
  r.ratio = -0.5;
  CHECK_THROWS_WITH(simplify_mesh(sphere, r).mesh, Catch::Contains("ratio must be in (0, 1]"));
  r.ratio = 1.5;
  CHECK_THROWS_WITH(simplify_mesh(sphere, r).mesh, Catch::Contains("ratio must be in (0, 1]"));
  r.ratio = 0.001;
  CHECK_THROWS_WITH(simplify_mesh(sphere, r).mesh, Catch::Contains("leaves no faces"));
  std::vector<double> w(sphere.vertex_count() + 1, 1.0);
  CHECK_THROWS_WITH(simplify_mesh(sphere, target(40), w).mesh, Catch::Contains("vertex weights"));
  w.assign(sphere.vertex_count(), 1.0);
  w[3] = -1;
  CHECK_THROWS_AS(simplify_mesh(sphere, target(40), w).mesh, Error);
  Mesh broken = sphere;
  broken.triangles[5] = 1000;
  CHECK_THROWS_WITH(simplify_mesh(broken, target(40)).mesh, Catch::Contains("out of range"));
}

TEST_CASE("simplify: degenerate input triangles are dropped, unreferenced vertices removed",
          "[simplify]") {
  Mesh m = make_sphere(1.0, 2);
  const size_t faces = m.triangle_count();
  m.triangles.insert(m.triangles.end(), {0, 0, 1, 2, 3, 3});
  m.positions.insert(m.positions.end(), {5.f, 5.f, 5.f});  // unreferenced
  const Simplified s = simplify_mesh(m, target(100));
  const Mesh& out = s.mesh;
  const SimplifyReport& rep = s.report;
  CHECK(rep.input_faces == faces);
  CHECK(out.triangle_count() == 100);
  CHECK(topology(out).unreferenced == 0);
  for (float x : out.positions) CHECK(std::fabs(x) < 1.5f);
}
