// Scoring a prediction against ground truth (SPEC section 7): evaluate_scores on vectors
// whose scores are worked out by hand below, AUC against an O(n^2) pair count, the text
// rows and their join, --transfer nearest against a brute-force nearest point, --smooth
// against the filter's all-pairs oracle, and evaluate_files' errors.
#include <catch2/catch.hpp>

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "cli/synthetic.h"
#include "core/mesh_points.h"
#include "meshsal/meshsal.h"
#include "saliency/gaussian_filter.h"
#include "test_io_util.h"

using meshsal::EvalScores;
using meshsal::evaluate_scores;
using meshsal_test::error_of;

namespace {

// AUC-q by counting pairs: positives are the ceil(q n) largest g and every g tied with the
// smallest of them; each (positive, negative) pair scores 1 when the positive's p is
// larger, 1/2 when equal.
double auc_pairs(const std::vector<double>& p, const std::vector<double>& g, double q) {
  std::vector<double> desc = g;
  std::sort(desc.rbegin(), desc.rend());
  const size_t top = std::max<size_t>(1, size_t(std::ceil(q * double(g.size()) - 1e-9)));
  const double t = desc[top - 1];
  double wins = 0, pairs = 0;
  for (size_t i = 0; i < p.size(); ++i)
    for (size_t j = 0; j < p.size(); ++j)
      if (g[i] >= t && g[j] < t) {
        pairs += 1;
        wins += p[i] > p[j] ? 1.0 : p[i] == p[j] ? 0.5 : 0.0;
      }
  return wins / pairs;
}

}  // namespace

TEST_CASE("eval: scores worked out by hand", "[eval]") {
  // p = 1 2 2 3 0, g = 0 5 1 5 0 (n = 5).
  // CC: mean p 1.6, mean g 2.2; deviations p -0.6 0.4 0.4 1.4 -1.6, g -2.2 2.8 -1.2 2.8 -2.2;
  //   sum dp dg = 1.32 + 1.12 - 0.48 + 3.92 + 3.52 = 9.4, sum dp^2 = 5.2, sum dg^2 = 26.8.
  // AUC-20%: ceil(0.2 * 5) = 1, the largest g is 5, tied twice: positives {1, 3} (p 2, 3),
  //   negatives {0, 2, 4} (p 1, 2, 0). Pairs: 2>1, 2=2 (1/2), 2>0, 3>all: 5.5 of 6.
  //   AUC-5%: ceil(0.25) = 1, the same positives.
  // NSS: g > 0 at {1, 2, 3}, p - mean 0.4 0.4 1.4 (mean 2.2/3), std p = sqrt(5.2 / 5).
  // KLD, SIM: P = p / 8 = 1/8 2/8 2/8 3/8 0; G = g / 11 = 0 5/11 1/11 5/11 0.
  //   SIM = 0 + 2/8 + 1/11 + 3/8 + 0; KLD = 5/11 ln((5/11)/(2/8)) + 1/11 ln((1/11)/(2/8))
  //   + 5/11 ln((5/11)/(3/8)) (eps 1e-12 changes the 12th digit).
  const EvalScores s = evaluate_scores({1, 2, 2, 3, 0}, {0, 5, 1, 5, 0});
  CHECK(s.vertices == 5);
  REQUIRE(s.cc);
  CHECK(*s.cc == Approx(9.4 / std::sqrt(5.2 * 26.8)).epsilon(1e-12));
  REQUIRE(s.auc_20);
  REQUIRE(s.auc_5);
  CHECK(*s.auc_20 == Approx(5.5 / 6).epsilon(1e-12));
  CHECK(*s.auc_5 == Approx(5.5 / 6).epsilon(1e-12));
  CHECK(s.positives_20 == 2);
  CHECK(s.positives_5 == 2);
  CHECK(s.threshold_20 == 5);
  REQUIRE(s.nss);
  CHECK(s.nss_vertices == 3);
  CHECK(*s.nss == Approx((2.2 / 3) / std::sqrt(5.2 / 5)).epsilon(1e-12));
  REQUIRE(s.sim);
  REQUIRE(s.kld);
  CHECK(*s.sim == Approx(2.0 / 8 + 1.0 / 11 + 3.0 / 8).epsilon(1e-12));
  const double kld = 5.0 / 11 * std::log((5.0 / 11) / (2.0 / 8)) + 1.0 / 11 * std::log((1.0 / 11) / (2.0 / 8)) +
                     5.0 / 11 * std::log((5.0 / 11) / (3.0 / 8));
  CHECK(*s.kld == Approx(kld).epsilon(1e-9));
  CHECK(s.notes.empty());

  // A perfect prediction: CC 1, AUC 1, KLD 0, SIM 1.
  const EvalScores same = evaluate_scores({0, 1, 2, 3, 4, 5, 6, 7, 8, 9}, {0, 1, 2, 3, 4, 5, 6, 7, 8, 9});
  CHECK(*same.cc == Approx(1));
  CHECK(*same.auc_20 == 1);
  CHECK(same.positives_20 == 2);  // the top 20% of 10: 9 and 8
  CHECK(same.positives_5 == 1);   // ceil(0.5) = 1: 9
  CHECK(std::fabs(*same.kld) < 1e-9);
  CHECK(*same.sim == Approx(1));

  // Negative values are shifted by their minimum: p = -1 0 1 -> 0 1 2 -> 0 1/3 2/3;
  // g = 0 0 1. SIM = min(2/3, 1) = 2/3; KLD = 1 ln(1 / (2/3)) = ln 1.5.
  const EvalScores neg = evaluate_scores({-1, 0, 1}, {0, 0, 1});
  CHECK(*neg.sim == Approx(2.0 / 3));
  CHECK(*neg.kld == Approx(std::log(1.5)));
}

TEST_CASE("eval: undefined scores are nullopt with a note and never NaN", "[eval]") {
  // p constant: CC and NSS undefined (std 0); AUC 1/2 (every pair ties); P uniform 1/3,
  // G = 0 1/3 2/3: SIM = 1/3 + 1/3, KLD = 1/3 ln 1 + 2/3 ln 2.
  const EvalScores c = evaluate_scores({2, 2, 2}, {0, 1, 2});
  CHECK(!c.cc);
  CHECK(!c.nss);
  CHECK(*c.auc_20 == 0.5);
  CHECK(*c.sim == Approx(2.0 / 3));
  CHECK(*c.kld == Approx(2.0 / 3 * std::log(2.0)));
  REQUIRE(c.notes.size() == 2);
  CHECK(c.notes[0].find("CC undefined: the prediction is constant") != std::string::npos);
  CHECK(c.notes[1].find("NSS undefined") != std::string::npos);

  // g all zero: CC (g constant), AUC (every vertex a positive), NSS (no g > 0), KLD and SIM
  // (g sums to 0) all undefined, each said.
  const EvalScores z = evaluate_scores({1, 2, 3}, {0, 0, 0});
  CHECK(!z.cc);
  CHECK(!z.auc_20);
  CHECK(!z.auc_5);
  CHECK(!z.nss);
  CHECK(!z.kld);
  CHECK(!z.sim);
  CHECK(z.notes.size() == 4);
  std::string all;
  for (const std::string& n : z.notes) all += n + "\n";
  CHECK(all.find("ground truth is constant") != std::string::npos);
  CHECK(all.find("no negatives") != std::string::npos);
  CHECK(all.find("no vertex has ground truth above 0") != std::string::npos);
  CHECK(all.find("ground truth sums to 0") != std::string::npos);

  // Refused: other lengths, fewer than 2 values, a value that is not finite (named).
  CHECK(error_of([] { evaluate_scores({1, 2}, {1, 2, 3}); }).find("same vertices") != std::string::npos);
  CHECK(error_of([] { evaluate_scores({1}, {1}); }).find("at least 2") != std::string::npos);
  CHECK(error_of([] { evaluate_scores({1, NAN, 3}, {1, 2, 3}); }) == "prediction value 1 is nan");
  CHECK(error_of([] { evaluate_scores({1, 2, 3}, {1, 2, INFINITY}); }) == "ground-truth value 2 is inf");
}

TEST_CASE("eval: AUC by sorting with average ranks equals the O(n^2) pair count", "[eval]") {
  std::mt19937 rng(7);
  for (int trial = 0; trial < 40; ++trial) {
    const size_t n = 2 + rng() % 60;
    std::vector<double> p(n), g(n);
    // Few distinct values, so that both have many ties.
    for (size_t i = 0; i < n; ++i) p[i] = double(rng() % 5), g[i] = double(rng() % 7) - 2;
    const EvalScores s = evaluate_scores(p, g);
    INFO("trial " << trial << ", n " << n);
    for (const auto& [q, auc] : {std::pair{0.20, s.auc_20}, std::pair{0.05, s.auc_5}}) {
      std::vector<double> desc = g;
      std::sort(desc.rbegin(), desc.rend());
      const bool has_negative = desc.back() < desc[std::max<size_t>(1, size_t(std::ceil(q * n - 1e-9))) - 1];
      REQUIRE(bool(auc) == has_negative);
      if (auc) CHECK(*auc == Approx(auc_pairs(p, g, q)).epsilon(1e-12));
    }
  }
}

TEST_CASE("eval: text rows are read with their line numbers and refused naming the line", "[eval][io]") {
  using meshsal::parse_vertex_rows;
  // A header, comments, commas or spaces; the value in the last column by default.
  const meshsal::VertexRows r = parse_vertex_rows("x,y,z,fixations,weight\n# comment\n\n0,0,0,5,0.5\n1 0 0 7 0.25\n",
                                                  "gt.csv");
  CHECK(r.columns == 5);
  CHECK(r.values == std::vector<double>{0.5, 0.25});
  CHECK(r.lines == std::vector<size_t>{4, 5});
  CHECK(r.xyz == std::vector<double>{0, 0, 0, 1, 0, 0});
  CHECK(parse_vertex_rows("0 0 0 5 0.5\n1 0 0 7 0.25\n", "gt.txt", 4).values == std::vector<double>{5, 7});
  auto err = [](const std::string& text, int column = 0) {
    return error_of([&] { parse_vertex_rows(text, "gt.txt", column); });
  };
  CHECK(err("0 0 0 1\n0 0 0 nan\n") == "gt.txt: line 2: the value (column 4) is not finite ('nan')");
  CHECK(err("0 0 0 1\n0 inf 0 2\n") == "gt.txt: line 2: coordinate y is not finite ('inf')");
  CHECK(err("0 0 0 1\n0 0 2\n") == "gt.txt: line 2: a row needs x y z and a value, got 3 fields");
  CHECK(err("0 0 0 1\n0 0 0 1 2\n") == "gt.txt: line 2: 5 fields, but the first row has 4");
  CHECK(err("0 0 0 1\n0 0 zero 1\n") == "gt.txt: line 2: field 3 'zero' is not a number");
  CHECK(err("0 0 0 1\n", 5) == "gt.txt: line 1: --gt-column 5 is beyond its 4 fields");
  CHECK(err("0 0 0 1\n", 3).find("must be 4 or more") != std::string::npos);
  CHECK(err("# nothing\n") == "gt.txt: no rows `x y z ... value` in it");
}

TEST_CASE("eval: rows join the vertex at their position within 1e-6 of the diagonal", "[eval][io]") {
  // A 2 x 2 plane of side 2 (9 vertices at x, y in {-1, 0, 1}), diagonal 2 sqrt 2; vertex 9
  // a duplicate of vertex 0 that no triangle uses.
  meshsal::Mesh m = meshsal::make_plane(2.0, 2);
  REQUIRE(m.vertex_count() == 9);
  const double x0 = m.origin[0] + m.positions[0], y0 = m.origin[1] + m.positions[1], z0 = m.origin[2] + m.positions[2];
  for (int k = 0; k < 3; ++k) m.positions.push_back(m.positions[k]);
  const double diag = 2 * std::sqrt(2.0), tol = 1e-6 * diag;
  auto model = [&](size_t v, int k) { return m.origin[k] + m.positions[3 * v + k]; };
  meshsal::VertexRows rows;
  auto add = [&](double x, double y, double z, double value, size_t line) {
    // (push_back: GCC 12 warns falsely of insert with an initializer list here)
    rows.xyz.push_back(x);
    rows.xyz.push_back(y);
    rows.xyz.push_back(z);
    rows.values.push_back(value);
    rows.lines.push_back(line);
  };
  add(x0, y0, z0, 3, 1);                                   // vertex 0 and its duplicate 9
  add(model(4, 0) + 0.5 * tol, model(4, 1), model(4, 2), 4, 2);  // within the tolerance
  add(model(8, 0) + 2 * tol, model(8, 1), model(8, 2), 8, 3);    // beyond it: unmatched
  add(x0, y0, z0, 3, 4);                                   // the same value again: fine
  add(5, 5, 5, 1, 5);                                      // far away: unmatched
  const meshsal::JoinedRows j = meshsal::join_vertex_rows(m, rows);
  CHECK(j.rows == 5);
  CHECK(j.matched_rows == 3);
  CHECK(j.unmatched_rows == 2);
  CHECK(j.unmatched_lines == std::vector<size_t>{3, 5});
  CHECK(j.has_value == std::vector<uint8_t>{1, 0, 0, 0, 1, 0, 0, 0, 0, 1});
  CHECK(j.values[0] == 3);
  CHECK(j.values[9] == 3);
  CHECK(j.values[4] == 4);
  CHECK(j.vertices_without_value == 7);
  // Two rows giving one vertex two values: refused, naming both lines.
  add(x0, y0, z0, 6, 6);
  CHECK(error_of([&] { meshsal::join_vertex_rows(m, rows); })
            .find("rows at lines 1 and 6 give vertex 0 two values (3 and 6)") != std::string::npos);
}

TEST_CASE("eval: rows join a mesh whose unused vertices lie far from its points", "[eval][io]") {
  // A unit triangle and vertex 3, used by no triangle, 1e15 away: the join's grid of cells
  // of 1e-6 of the diagonal numbered its cell beyond int64_t (undefined behaviour, which the
  // sanitizer build and the fuzz target rows report). Rows reach it and the corners alike.
  const double xyz[12] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 1e15, 0, 0};
  const uint32_t tri[3] = {0, 1, 2};
  const meshsal::Mesh m = meshsal::make_mesh(xyz, 4, tri, 3);
  const meshsal::JoinedRows j =
      meshsal::join_vertex_rows(m, meshsal::parse_vertex_rows("0 0 0 1\n1 0 0 2\n1e15 0 0 3\n0.5 0 0 4\n", "gt.txt"));
  CHECK(j.matched_rows == 3);
  CHECK(j.unmatched_lines == std::vector<size_t>{4});
  CHECK(j.has_value == std::vector<uint8_t>{1, 1, 0, 1});
  CHECK(j.values == std::vector<double>{1, 2, 0, 3});
}

TEST_CASE("eval: transfer_nearest takes the nearest point's value and the lowest index of ties", "[eval]") {
  const meshsal::Mesh target = meshsal::make_sphere(1.0, 2);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1.2, 1.2);
  std::vector<double> xyz, values;
  for (int i = 0; i < 300; ++i) {
    for (int k = 0; k < 3; ++k) xyz.push_back(u(rng));
    values.push_back(i);
  }
  // A second point at point 10's position: ties go to 10.
  for (int k = 0; k < 3; ++k) xyz.push_back(xyz[30 + k]);
  values.push_back(-1);
  const meshsal::NearestValues t = meshsal::transfer_nearest(xyz, values, target);
  REQUIRE(t.values.size() == target.vertex_count());
  double worst = 0;
  for (size_t v = 0; v < target.vertex_count(); ++v) {
    double best = HUGE_VAL;
    size_t best_i = 0;
    for (size_t i = 0; i < values.size(); ++i) {
      double d = 0;
      for (int k = 0; k < 3; ++k) {
        const double e = float(xyz[3 * i + k] - target.origin[k]) - double(target.positions[3 * v + k]);
        d += e * e;
      }
      if (d < best) best = d, best_i = i;
    }
    INFO("vertex " << v);
    CHECK(t.values[v] == values[best_i]);
    worst = std::max(worst, std::sqrt(best));
  }
  CHECK(t.max_distance == Approx(worst));
  // A target vertex exactly at the doubled point takes the lower index.
  meshsal::Mesh one = target;
  for (int k = 0; k < 3; ++k) one.positions[k] = float(xyz[30 + k] - one.origin[k]);
  CHECK(meshsal::transfer_nearest(xyz, values, one).values[0] == 10);
}

TEST_CASE("eval: smoothing is the library's Gaussian filter and keeps unused vertices", "[eval]") {
  meshsal::Mesh m = meshsal::make_sphere(1.0, 2);
  const size_t n = m.vertex_count();
  for (int k = 0; k < 3; ++k) m.positions.push_back(0.f);  // an unused vertex at the centre
  std::vector<double> p(n + 1);
  for (size_t v = 0; v <= n; ++v) p[v] = std::sin(3.0 * m.positions[3 * v]) + (v == n ? 10 : 0);
  const std::vector<double> s = meshsal::smooth_vertex_values(m, p, 0.05, 1);
  const std::vector<uint8_t> is_point = meshsal::referenced_vertices(m);
  const double sigma = 0.05 * meshsal::mesh_points_bbox(m, is_point).diagonal();
  const std::vector<double> oracle = meshsal::gaussian_filter_bruteforce(m, is_point, p, {sigma})[0];
  for (size_t v = 0; v < n; ++v) CHECK(s[v] == Approx(oracle[v]).epsilon(1e-12).margin(1e-14));
  CHECK(s[n] == p[n]);
  CHECK(error_of([&] { meshsal::smooth_vertex_values(m, p, 0.6); }).find("(0, 0.5]") != std::string::npos);
}

TEST_CASE("eval: evaluate_files reads and joins or carries and refuses what it cannot score", "[eval]") {
  meshsal_test::TempDir dir;
  const meshsal::Mesh m = meshsal::make_sphere(1.0, 2);
  const size_t n = m.vertex_count();
  std::vector<double> p(n), g(n), other(n);
  for (size_t v = 0; v < n; ++v) {
    p[v] = 1 + m.positions[3 * v];
    g[v] = std::max(0.0, double(m.positions[3 * v] + 0.3 * m.positions[3 * v + 1]));
    other[v] = m.positions[3 * v + 2];
  }
  const std::string pred = dir.file("pred.ply"), gt = dir.file("gt.ply");
  meshsal::write_ply(pred, m, {{"quality", &p}, {"other", &other}});
  meshsal::write_ply(gt, m, {{"quality", &g}});
  // Same vertices: the scores of the values as written (float).
  std::vector<double> pf(n), gf(n);
  for (size_t v = 0; v < n; ++v) pf[v] = float(p[v]), gf[v] = float(g[v]);
  const meshsal::EvalReport r = meshsal::evaluate_files(pred, gt);
  const EvalScores direct = evaluate_scores(pf, gf);
  CHECK(r.vertices == n);
  CHECK(r.raw.vertices == n);
  CHECK(*r.raw.cc == *direct.cc);
  CHECK(*r.raw.auc_20 == *direct.auc_20);
  CHECK(*r.raw.kld == *direct.kld);
  CHECK(!r.smoothed);
  CHECK(!r.gt_is_text);

  // --smooth: the raw scores unchanged, the smoothed ones beside them.
  meshsal::EvalOptions so;
  so.smooth = 0.05;
  const meshsal::EvalReport rs = meshsal::evaluate_files(pred, gt, so);
  CHECK(*rs.raw.cc == *r.raw.cc);
  REQUIRE(rs.smoothed);
  const EvalScores sm = evaluate_scores(meshsal::smooth_vertex_values(m, pf, 0.05), gf);
  CHECK(*rs.smoothed->cc == Approx(*sm.cc).epsilon(1e-6));
  CHECK(*rs.smoothed->cc != *r.raw.cc);

  // Text rows at the vertices' positions (the last column, after an extra one).
  std::string text = "x y z count value\n";
  for (size_t v = 0; v < n; ++v) {
    char line[160];
    std::snprintf(line, sizeof line, "%.9g %.9g %.9g 1 %.9g\n", m.origin[0] + m.positions[3 * v],
                  m.origin[1] + m.positions[3 * v + 1], m.origin[2] + m.positions[3 * v + 2], gf[v]);
    text += line;
  }
  text += "7 7 7 1 0.5\n";  // matches nothing
  const std::string rows = dir.write("gt.txt", text);
  const meshsal::EvalReport rt = meshsal::evaluate_files(pred, rows);
  CHECK(rt.gt_is_text);
  CHECK(rt.gt_column == 5);
  CHECK(rt.gt_rows == n + 1);
  CHECK(rt.matched_rows == n);
  CHECK(rt.unmatched_rows == 1);
  CHECK(rt.unmatched_lines == std::vector<size_t>{n + 2});
  CHECK(*rt.raw.cc == Approx(*direct.cc).epsilon(1e-7));  // the rows' 9 digits of each float
  REQUIRE(rt.notes.size() == 1);
  CHECK(rt.notes[0].find("1 of " + std::to_string(n + 1) + " ground-truth rows matched no vertex") != std::string::npos);

  // The same rows gzipped: read alike.
  const std::string rows_gz = dir.write_gz("gt.txt.gz", text);
  const meshsal::EvalReport rz = meshsal::evaluate_files(pred, rows_gz);
  CHECK(rz.gt_is_text);
  CHECK(*rz.raw.cc == *rt.raw.cc);

  // PRED as glTF: S as _SALIENCY, read as quality; the same scores.
  const std::string pred_glb = dir.file("pred.glb");
  meshsal::write_gltf(pred_glb, m, p);
  const meshsal::EvalReport rg = meshsal::evaluate_files(pred_glb, gt);
  REQUIRE(rg.raw.cc);
  CHECK(*rg.raw.cc == *direct.cc);
  CHECK(*rg.raw.auc_5 == *direct.auc_5);

  // Another attribute of PRED.
  meshsal::EvalOptions oa;
  oa.attribute = "other";
  CHECK(meshsal::evaluate_files(pred, gt, oa).raw.cc != r.raw.cc);

  // GT on another mesh: refused without --transfer, carried with it.
  const meshsal::Mesh fine = meshsal::make_sphere(1.0, 3);
  std::vector<double> gfine(fine.vertex_count());
  for (size_t v = 0; v < fine.vertex_count(); ++v)
    gfine[v] = std::max(0.0, double(fine.positions[3 * v] + 0.3 * fine.positions[3 * v + 1]));
  const std::string gt_fine = dir.file("gt_fine.ply");
  meshsal::write_ply(gt_fine, fine, {{"quality", &gfine}});
  CHECK(error_of([&] { meshsal::evaluate_files(pred, gt_fine); }) ==
        gt_fine + ": " + std::to_string(fine.vertex_count()) + " vertices, PRED has " + std::to_string(n) +
            ": not PRED's vertices (--transfer nearest carries the ground truth to them)");
  meshsal::EvalOptions on;
  on.transfer = meshsal::EvalTransfer::Nearest;
  const meshsal::EvalReport rn = meshsal::evaluate_files(pred, gt_fine, on);
  CHECK(rn.transferred);
  // The icosphere's level-2 vertices are level-3 vertices: each finds itself.
  CHECK(rn.transfer_max_distance < 1e-6);
  CHECK(*rn.raw.cc == Approx(*direct.cc).epsilon(1e-6));

  // Errors, each naming what is wrong.
  CHECK(error_of([&] { meshsal::EvalOptions o; o.attribute = "nope"; meshsal::evaluate_files(pred, gt, o); }) ==
        pred + ": no per-vertex attribute 'nope' (it has: quality, other; --attribute names another; S is PLY's "
               "quality or glTF's _SALIENCY)");
  std::vector<double> bad = p;
  bad[4] = NAN;
  const std::string pred_nan = dir.file("pred_nan.ply");
  meshsal::write_ply(pred_nan, m, {{"quality", &bad}});
  CHECK(error_of([&] { meshsal::evaluate_files(pred_nan, gt); }) == pred_nan + ": attribute 'quality' of vertex 4 is nan");
  meshsal::Mesh moved = m;
  moved.positions[3 * 5] += 0.01f;
  const std::string gt_moved = dir.file("gt_moved.ply");
  meshsal::write_ply(gt_moved, moved, {{"quality", &g}});
  CHECK(error_of([&] { meshsal::evaluate_files(pred, gt_moved); }).find(": vertex 5 is at (") != std::string::npos);
  const std::string one_row = dir.write("one.txt", "7 7 7 1\n0.5 0.5 0.5 1\n");
  CHECK(error_of([&] { meshsal::evaluate_files(pred, one_row); })
            .find("only 0 of PRED's " + std::to_string(n) + " vertices have ground truth: scoring needs at least 2") !=
        std::string::npos);
}
