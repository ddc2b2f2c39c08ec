// The one view pipeline (best_viewpoint with ViewpointOptions): every front end gives the same
// view at the same settings, the up axis is a frame (a mesh turned z-up, searched with up Z,
// gives the y-up angles), the elevation range bounds the search, bad ranges are refused.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "cli_run.h"
#include "cli/synthetic.h"
#include "json_check.h"
#include "meshsal/meshsal.h"
#include "test_util.h"

using namespace meshsal;
using namespace meshsal_test;

namespace {

const double kDeg = 180.0 / 3.14159265358979323846;

std::string g9(double x) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.9g", x);
  return buf;
}

// The text of the number after the first "KEY": in `text` (as printed), "" when absent.
std::string json_text(const std::string& text, const std::string& key, size_t from = 0) {
  const std::string k = "\"" + key + "\": ";
  const size_t at = text.find(k, from);
  if (at == std::string::npos) return "";
  const size_t b = at + k.size();
  const size_t e = text.find_first_of(",}\n", b);
  return text.substr(b, e - b);
}

// Search options of the library tests: a visibility RESOLUTION, RESTARTS, and VIEWS directions
// also scored exhaustively (0: none, ViewpointOptions' default).
ViewpointOptions search_options(int resolution, int restarts, int views = 0) {
  ViewpointOptions o;
  o.visibility.resolution = resolution;
  o.optimiser.restarts = restarts;
  o.views = views;
  return o;
}

// Two searches that must find the same best view, to the bit.
void check_same_view(const Viewpoint& a, const Viewpoint& b) {
  CHECK(a.view.theta == b.view.theta);
  CHECK(a.view.phi == b.view.phi);
}

// A bumpy sphere whose score is max(0, y + 0.3 x): best seen from above, a little to +x.
std::vector<double> top_score(const Mesh& m) {
  std::vector<double> s(m.vertex_count());
  for (size_t i = 0; i < s.size(); ++i)
    s[i] = std::max(0.0, double(m.positions[3 * i + 1]) + 0.3 * double(m.positions[3 * i]));
  return s;
}

}  // namespace

TEST_CASE("view pipeline: viewpoint, render --best, batch --view and the library give one view", "[view][cli]") {
  MESHSAL_REQUIRE_MESH(mesh, "bunny_3k.off");
  TempDir dir;
  const std::string dp = dir.path.string();
  const Mesh m = load_mesh(mesh);
  SaliencyOptions so;
  const std::vector<double> s = compute_saliency(m, so).saliency;
  // The defaults, an elevation range, and other search settings: each command takes them all.
  ViewpointOptions other;
  other.optimiser.restarts = 3;
  other.optimiser.seed = 5;
  other.visibility.resolution = 256;
  other.visibility.depth_tol_px = 1.5;
  const std::vector<std::pair<std::string, ViewpointOptions>> settings{
      {"", ViewpointOptions{}},
      {" --elevation 0,40", [] { ViewpointOptions o; o.elevation = {0, 40}; return o; }()},
      {" --restarts 3 --seed 5 --resolution 256 --depth-tol 1.5", other}};
  for (const auto& [el, vo] : settings) {
    INFO("settings:" << el);
    const CliRun vp = run_cli("viewpoint " + quoted(mesh) + " --backend cpu --json" + el, dir);
    REQUIRE(vp.rc == 0);
    const CliRun rb = run_cli("render " + quoted(mesh) + " --best --backend cpu --size 64 -o " +
                                  quoted(dp + "/r.png") + " --json" + el, dir);
    REQUIRE(rb.rc == 0);
    const std::string out = dp + "/batch";
    std::filesystem::remove_all(out);
    const CliRun ba = run_cli("batch " + quoted(mesh) + " -o " + quoted(out) + " --view --backend cpu --size 64 -q" + el, dir);
    REQUIRE(ba.rc == 0);
    const std::string log = read_file(out + "/batch.jsonl");
    const size_t view_at = log.find("\"view\": {");
    REQUIRE(view_at != std::string::npos);

    const Viewpoint v = best_viewpoint(m, s, vo);
    for (const char* key : {"theta_deg", "phi_deg"}) {
      INFO(key);
      const std::string lib = g9((std::string(key) == "theta_deg" ? v.view.theta : v.view.phi) * kDeg);
      CHECK(json_text(vp.out, key) == lib);
      CHECK(json_text(rb.out, key) == lib);
      CHECK(json_text(log, key, view_at) == lib);
    }
    CHECK(json_text(vp.out, "theta") == g9(v.view.theta));
    CHECK(json_text(rb.out, "theta") == g9(v.view.theta));
    CHECK(json_text(vp.out, "phi") == g9(v.view.phi));
    CHECK(json_text(rb.out, "phi") == g9(v.view.phi));
    CHECK(json_text(vp.out, "visible_score") == g9(v.U));
    CHECK(json_text(log, "visible_score", view_at) == g9(v.U));
    CHECK(json_text(vp.out, "visible_fraction") == g9(v.visible_fraction));
    CHECK(v.view.phi * kDeg >= vo.elevation.min);
    CHECK(v.view.phi * kDeg <= vo.elevation.max + 1e-9);
  }
}

TEST_CASE("view pipeline: a mesh turned z-up, searched with up z, gives the y-up angles", "[view]") {
  const Mesh y_up = make_bumpy_sphere(3);
  const std::vector<double> score = top_score(y_up);
  // The frame of up z: frame x = mesh x, frame y = mesh z, frame z = mesh -y; a y-up point
  // (x, y, z) lies at x ex + y ez + z (-ey) = (x, -z, y) in the z-up mesh.
  Mesh z_up = y_up;
  for (size_t i = 0; i < z_up.vertex_count(); ++i) {
    const float x = y_up.positions[3 * i], y = y_up.positions[3 * i + 1], z = y_up.positions[3 * i + 2];
    z_up.positions[3 * i] = x;
    z_up.positions[3 * i + 1] = -z;
    z_up.positions[3 * i + 2] = y;
  }
  ViewpointOptions o = search_options(96, 3, 60);
  const Viewpoint a = best_viewpoint(y_up, score, o);
  o.up = UpAxis::Z;
  const Viewpoint b = best_viewpoint(z_up, score, o);
  check_same_view(a, b);
  CHECK(a.U == b.U);
  CHECK(a.map.best == b.map.best);
  CHECK(a.map.U == b.map.U);
  CHECK(b.up == UpAxis::Z);
  CHECK(a.view.phi > 0.5);  // from above: the score is on top
  // The camera turns with the mesh: y-up (dx, dy, dz) is (dx, -dz, dy) z-up.
  CHECK(b.camera.direction[0] == Approx(a.camera.direction[0]).margin(1e-12));
  CHECK(b.camera.direction[1] == Approx(-a.camera.direction[2]).margin(1e-12));
  CHECK(b.camera.direction[2] == Approx(a.camera.direction[1]).margin(1e-12));
  CHECK(b.camera.up[2] == Approx(a.camera.up[1]).margin(1e-12));
  // The elevation range is taken in the up frame too.
  o.elevation = {-20, 20};
  const Viewpoint c = best_viewpoint(z_up, score, o);
  o.up = UpAxis::Y;
  const Viewpoint d = best_viewpoint(y_up, score, o);
  check_same_view(c, d);
}

TEST_CASE("view pipeline: the elevation range bounds the search", "[view]") {
  const Mesh s = make_bumpy_sphere(3);
  const std::vector<double> score = top_score(s);
  ViewpointOptions o = search_options(96, 4, 200);
  o.elevation = {-90, 90};  // the paper's search, over the whole sphere
  const Viewpoint free = best_viewpoint(s, score, o);
  REQUIRE(free.view.phi * kDeg > 40);  // the optimum is high above the horizon
  o.elevation = {-30, 20};
  const Viewpoint bound = best_viewpoint(s, score, o);
  const double lo = -30 / kDeg - 1e-12, hi = 20 / kDeg + 1e-12;
  CHECK(bound.view.phi >= lo);
  CHECK(bound.view.phi <= hi);
  CHECK(bound.view.phi != free.view.phi);
  CHECK(bound.view.phi * kDeg == Approx(20).margin(1.5));  // as high as the range allows
  CHECK(bound.U < free.U);
  for (const ViewAngles& a : bound.optimised.starts) CHECK((a.phi >= lo && a.phi <= hi));
  for (const ViewAngles& a : bound.optimised.finals) CHECK((a.phi >= lo && a.phi <= hi));
  REQUIRE(bound.map.views.size() == 200);
  for (const ViewAngles& a : bound.map.views) CHECK((a.phi >= lo && a.phi <= hi));
  // The band's map covers it: its lowest and highest directions near the ends.
  double pmin = 10, pmax = -10;
  for (const ViewAngles& a : bound.map.views) pmin = std::min(pmin, a.phi), pmax = std::max(pmax, a.phi);
  CHECK(pmin * kDeg < -28);
  CHECK(pmax * kDeg > 18);
  // One latitude only: every view on it.
  o.elevation = {10, 10};
  const Viewpoint ring = best_viewpoint(s, score, o);
  CHECK(ring.view.phi * kDeg == Approx(10).margin(1e-9));
  // The default band: a photographer's view, as high as it allows here.
  o.elevation = ElevationRange{};
  CHECK(o.elevation.min == kDefaultElevationMin);
  CHECK(o.elevation.max == kDefaultElevationMax);
  const Viewpoint band = best_viewpoint(s, score, o);
  CHECK(band.view.phi * kDeg >= kDefaultElevationMin);
  CHECK(band.view.phi * kDeg == Approx(kDefaultElevationMax).margin(1.5));
  CHECK(ViewpointOptions{}.elevation.min == kDefaultElevationMin);
}

TEST_CASE("view pipeline: bad elevation ranges and names are refused with Error", "[view]") {
  const Mesh s = make_bumpy_sphere(2);
  const std::vector<double> score = top_score(s);
  ViewpointOptions o = search_options(32, 1);
  for (const ElevationRange r : {ElevationRange{30, 10}, ElevationRange{-91, 0}, ElevationRange{0, 90.5},
                                 ElevationRange{std::nan(""), 10}, ElevationRange{-100, 100}}) {
    o.elevation = r;
    INFO(r.min << ", " << r.max);
    CHECK_THROWS_AS(best_viewpoint(s, score, o), Error);
    try {
      best_viewpoint(s, score, o);
    } catch (const Error& e) {
      CHECK(std::string(e.what()).find("--") == std::string::npos);  // no CLI flag names
      CHECK(std::string(e.what()).find("elevation range") != std::string::npos);
    }
  }
  CHECK_THROWS_WITH(parse_elevation_range("10,-10"),
                    "elevation range must have -90 <= min <= max <= 90 degrees, got min 10, max -10");
  CHECK_THROWS_WITH(parse_elevation_range("10"), "elevation range must be MIN,MAX in degrees (e.g. 0,60), got '10'");
  CHECK_THROWS_AS(parse_elevation_range("a,b"), Error);
  CHECK(parse_elevation_range("-10,45.5").max == 45.5);
  CHECK(parse_up_axis("z") == UpAxis::Z);
  CHECK(parse_up_axis("-x") == UpAxis::MinusX);
  CHECK(parse_up_axis("+y") == UpAxis::Y);
  CHECK_THROWS_WITH(parse_up_axis("w"), "up must be x, y, z, -x, -y or -z, got 'w'");
  CHECK(parse_backend("gpu") == Backend::Gpu);
  CHECK_THROWS_WITH(parse_backend("tpu"), "backend must be auto, cpu or gpu, got 'tpu'");
}

TEST_CASE("view pipeline: the camera of a view renders that view", "[view]") {
  const Mesh s = make_bumpy_sphere(3);
  const std::vector<double> score = top_score(s);
  RenderStyle style;
  style.size = 48;
  style.up = UpAxis::Z;
  const ViewAngles view{0.7, -0.3};
  const ViewCamera c = view_camera(s, view, UpAxis::Z);
  const Image a = render_view(s, score, view, style);
  RenderStyle other = style;
  other.up = UpAxis::Y;  // not read: the camera has its up axis
  const Image b = render_camera_view(s, score, c, other);
  CHECK(a.rgb == b.rgb);
  double dot = 0, du = 0, dd = 0, len = 0;
  for (int k = 0; k < 3; ++k) {
    dot += c.up[k] * c.direction[k];
    du += c.up[k] * c.up[k];
    dd += c.direction[k] * c.direction[k];
    len += (c.eye[k] - c.target[k]) * c.direction[k];
  }
  CHECK(dot == Approx(0).margin(1e-12));
  CHECK(du == Approx(1));
  CHECK(dd == Approx(1));
  CHECK(len > 0);
  CHECK(c.half_extent > 0);
  CHECK(c.up[2] > 0);  // z up: the picture's up leans to +z at this latitude
}
