// Issue 22 (1): local coordinates. A scan at survey coordinates (x ~ 5e5, y ~ 4e6) gets the
// saliency, simplification, view and distances of the same scan at the origin, and written
// positions keep the input's precision (SPEC section 6).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "cli_run.h"
#include "cli/synthetic.h"
#include "meshsal/meshsal.h"
#include "test_util.h"

using namespace meshsal;
using namespace meshsal_test;
namespace fs = std::filesystem;

namespace {

const double kShift[3] = {5e5, 4e6, 100};

// A 25 m "scan": the bumpy sphere (a unique feature and ~900 bumps) at radius 12.5, as
// doubles, shifted by `shift`.
std::vector<double> scan_coordinates(const Mesh& unit, const double* shift) {
  std::vector<double> xyz(unit.positions.size());
  for (size_t i = 0; i < xyz.size(); ++i) xyz[i] = 12.5 * double(unit.positions[i]) + (shift ? shift[i % 3] : 0.0);
  return xyz;
}

// OBJ text with every coordinate's 17 significant digits (a double read back exactly).
void write_obj_text(const std::string& path, const std::vector<double>& xyz, const std::vector<uint32_t>& tri) {
  std::ofstream f(path);
  char line[128];
  for (size_t v = 0; v < xyz.size() / 3; ++v) {
    std::snprintf(line, sizeof line, "v %.17g %.17g %.17g\n", xyz[3 * v], xyz[3 * v + 1], xyz[3 * v + 2]);
    f << line;
  }
  for (size_t t = 0; t < tri.size(); t += 3) f << "f " << tri[t] + 1 << ' ' << tri[t + 1] + 1 << ' ' << tri[t + 2] + 1 << '\n';
}

double max_of(const std::vector<double>& v) { return *std::max_element(v.begin(), v.end()); }

double diagonal_of(const std::vector<double>& xyz) {
  double lo[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
  for (size_t i = 0; i < xyz.size(); ++i) {
    lo[i % 3] = std::min(lo[i % 3], xyz[i]);
    hi[i % 3] = std::max(hi[i % 3], xyz[i]);
  }
  return std::sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) + (hi[2] - lo[2]) * (hi[2] - lo[2]));
}

std::string file_text(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

struct Scans {
  fs::path dir;
  std::string origin_obj, utm_obj;
  std::vector<double> origin_xyz, utm_xyz;
  std::vector<uint32_t> triangles;
};

Scans make_scans(const char* name) {
  Scans s;
  s.dir = scratch_dir(name);
  const Mesh unit = make_bumpy_sphere(3);
  s.triangles = unit.triangles;
  s.origin_xyz = scan_coordinates(unit, nullptr);
  s.utm_xyz = scan_coordinates(unit, kShift);
  s.origin_obj = (s.dir / "scan_origin.obj").string();
  s.utm_obj = (s.dir / "scan_utm.obj").string();
  write_obj_text(s.origin_obj, s.origin_xyz, s.triangles);
  write_obj_text(s.utm_obj, s.utm_xyz, s.triangles);
  return s;
}

}  // namespace

TEST_CASE("coordinates: a scan at survey coordinates gets the saliency of the scan at the origin", "[coordinates]") {
  const Scans s = make_scans("coords_saliency");
  const Mesh at0 = load_mesh(s.origin_obj), utm = load_mesh(s.utm_obj);
  // The origin is the bounding box's centre, in double; the local floats agree.
  CHECK(std::fabs(utm.origin[1] - 4e6) < 1);
  CHECK(std::fabs(utm.origin[0] - at0.origin[0] - kShift[0]) < 1e-9);
  const SaliencyResult r0 = compute_saliency(at0, {}), ru = compute_saliency(utm, {});
  const double top = max_of(r0.saliency);
  double worst = 0;
  for (size_t v = 0; v < r0.saliency.size(); ++v) worst = std::max(worst, std::fabs(r0.saliency[v] - ru.saliency[v]));
  CHECK(worst <= 1e-5 * top);

  // What the test guards against: the same coordinates rounded to float where they lie (the
  // old loaders) give another saliency.
  Mesh naive;
  naive.triangles = s.triangles;
  naive.positions.assign(s.utm_xyz.begin(), s.utm_xyz.end());
  const SaliencyResult rn = compute_saliency(naive, {});
  double naive_worst = 0;
  for (size_t v = 0; v < r0.saliency.size(); ++v) naive_worst = std::max(naive_worst, std::fabs(r0.saliency[v] - rn.saliency[v]));
  CHECK(naive_worst > 1e-2 * top);

  // The view: the same angles and score.
  ViewpointOptions vo;
  vo.optimiser.restarts = 2;
  const Viewpoint b0 = best_viewpoint(at0, r0.saliency, vo), bu = best_viewpoint(utm, ru.saliency, vo);
  CHECK(b0.view.theta == bu.view.theta);
  CHECK(b0.view.phi == bu.view.phi);
  CHECK(std::fabs(b0.U - bu.U) <= 1e-9 * b0.U);
}

TEST_CASE("coordinates: the saliency PLY of a survey scan keeps its positions to the last digit", "[coordinates][cli]") {
  const Scans s = make_scans("coords_cli_saliency");
  const std::string out = (s.dir / "s.ply").string();
  const CliRun r = run_cli("saliency " + quoted(s.utm_obj) + " -o " + quoted(out) + " -q", s.dir);
  REQUIRE(r.rc == 0);
  // Float would move them by up to 0.25 m: the positions are written in double...
  CHECK(file_text(out).find("property double x\nproperty double y\nproperty double z\n") != std::string::npos);
  // ...and each as it was read.
  const Mesh back = load_mesh(out);
  CHECK(back.double_positions);
  CHECK(model_positions(back) == s.utm_xyz);
  // simplify reads that saliency back for the same scan (compared in the file's coordinates).
  const CliRun r2 = run_cli("simplify " + quoted(s.utm_obj) + " --saliency-from " + quoted(out) + " --ratio 0.5 -o " +
                                quoted((s.dir / "half.ply").string()) + " -q",
                            s.dir);
  CHECK(r2.rc == 0);
  CHECK(r2.err.empty());
}

TEST_CASE("coordinates: simplification and distances of a survey scan are those at the origin", "[coordinates][cli]") {
  const Scans s = make_scans("coords_cli_simplify");
  for (const char* ext : {".ply", ".obj"}) {
    const std::string out0 = (s.dir / (std::string("s0") + ext)).string(), outu = (s.dir / (std::string("su") + ext)).string();
    REQUIRE(run_cli("simplify " + quoted(s.origin_obj) + " --ratio 0.2 -o " + quoted(out0) + " -q", s.dir).rc == 0);
    REQUIRE(run_cli("simplify " + quoted(s.utm_obj) + " --ratio 0.2 -o " + quoted(outu) + " -q", s.dir).rc == 0);
    const Mesh m0 = load_mesh(out0), mu = load_mesh(outu);
    REQUIRE(m0.triangles == mu.triangles);
    const std::vector<double> p0 = model_positions(m0), pu = model_positions(mu);
    const double diag = diagonal_of(s.origin_xyz);
    double worst = 0;
    for (size_t i = 0; i < p0.size(); ++i) worst = std::max(worst, std::fabs(pu[i] - kShift[i % 3] - p0[i]));
    CHECK(worst <= 1e-7 * diag);
    // The distances between two files with two origins: as at the origin.
    const SurfaceComparison c0 = compare_surfaces(load_mesh(s.origin_obj), m0, {});
    const SurfaceComparison cu = compare_surfaces(load_mesh(s.utm_obj), mu, {});
    CHECK(cu.rms == Approx(c0.rms).epsilon(1e-6));
    CHECK(cu.hausdorff == Approx(c0.hausdorff).epsilon(1e-6));
    CHECK(c0.rms > 0);
  }
}

TEST_CASE("coordinates: unmoved vertices are written as they were read", "[coordinates][io]") {
  const fs::path dir = scratch_dir("coords_roundtrip");
  // A float PLY off the origin: loading localizes it, writing gives back the same bytes.
  Mesh hand = make_bumpy_sphere(2);
  for (size_t i = 0; i < hand.positions.size(); ++i) hand.positions[i] = hand.positions[i] * 3.f + (i % 3 == 1 ? 0.7f : 0.f);
  const std::string a = (dir / "a.ply").string(), b = (dir / "b.ply").string();
  write_ply(a, hand, {});
  const Mesh loaded = load_mesh(a);
  CHECK(loaded.origin[1] != 0);
  write_ply(b, loaded, {});
  CHECK(file_text(a) == file_text(b));
  // OBJ text keeps the digits it was written with (up to 9; beyond that a float holds them
  // within 1e-7 of the diagonal, and the float's shortest text is written).
  const std::string t = (dir / "t.obj").string(), u = (dir / "u.obj").string();
  { std::ofstream(t) << "v 0.123456789 1 2\nv 1.5 2.00000001 3\nv 0 0 3.25\nf 1 2 3\n"; }
  write_obj(u, load_mesh(t));
  CHECK(file_text(u) == "# written by meshsal\nv 0.123456789 1 2\nv 1.5 2.00000001 3\nv 0 0 3.25\nf 1 2 3\n");
  // A PLY with double coordinates is written with double ones.
  Mesh d = load_mesh(t);
  d.double_positions = true;
  write_ply(a, d, {});
  const Mesh dback = load_mesh(a);
  CHECK(dback.double_positions);
  CHECK(model_positions(dback) == std::vector<double>{0.123456789, 1, 2, 1.5, 2.00000001, 3, 0, 0, 3.25});
  // A moved vertex is written from its new position.
  Mesh moved = load_mesh(t);
  moved.positions[0] += 1.0f;
  const std::vector<double> mp = model_positions(moved);
  CHECK(mp[0] == double(moved.positions[0]) + moved.origin[0]);
  CHECK(mp[1] == 1);
}

TEST_CASE("coordinates: make_mesh localizes float and double arrays alike", "[coordinates]") {
  const std::vector<double> xyz = {5e5, 4e6 + 0.3, 100, 5e5 + 1, 4e6 + 0.3, 100, 5e5, 4e6 + 1.3, 100.5};
  const std::vector<uint32_t> tri = {0, 1, 2};
  const Mesh m = make_mesh(xyz.data(), 3, tri.data(), 3);
  CHECK_FALSE(m.double_positions);  // a file's property: writers decide by what the values need
  CHECK(m.origin[0] == 5e5 + 0.5);
  CHECK(m.positions[0] == -0.5f);
  CHECK(model_positions(m) == xyz);
  CHECK(positions_need_double(m));  // 4e6 + 0.3 in float is 4e6 + 0.25
  // Far from the origin in float: the float values themselves come back, and float will do.
  std::vector<float> f(xyz.begin(), xyz.end());
  const Mesh mf = make_mesh(f.data(), 3, tri.data(), 3);
  CHECK_FALSE(mf.double_positions);
  const std::vector<double> back = model_positions(mf);
  for (size_t i = 0; i < f.size(); ++i) CHECK(back[i] == double(f[i]));
  CHECK_FALSE(positions_need_double(mf));
}
