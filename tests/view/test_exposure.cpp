// Exposure, the perceptual model's cue of what a viewer can see (view/exposure.h): against
// its plain oracle, on cases with a known answer (a sphere hidden inside another, the
// bottom of a cube that views from above never see, the middle of a long bar nearer the
// views' centres than its ends), and the same bits on any thread count.
#include <algorithm>
#include <cmath>

#include "cli/synthetic.h"
#include "meshsal/meshsal.h"
#include "view/camera.h"
#include "view/exposure.h"
#include "test_util.h"

using namespace meshsal;

namespace {

VisibilityOptions coarse(unsigned threads = 0) {
  VisibilityOptions v;
  v.resolution = 128;
  v.threads = threads;
  return v;
}

std::vector<double> exposure(const Mesh& mesh, ExposureWeighting w, unsigned threads = 0) {
  return exposure_cpu(mesh, exposure_normals(mesh), frame_mesh(mesh), exposure_views(), w, coarse(threads));
}

// Two meshes as one (b's indices after a's vertices).
Mesh joined(const Mesh& a, const Mesh& b) {
  Mesh m = a;
  const uint32_t base = uint32_t(a.vertex_count());
  m.positions.insert(m.positions.end(), b.positions.begin(), b.positions.end());
  for (uint32_t t : b.triangles) m.triangles.push_back(base + t);
  return m;
}

double max_of(const std::vector<double>& v) { return *std::max_element(v.begin(), v.end()); }

}  // namespace

TEST_CASE("the exposure views ring the default band") {
  const std::vector<ViewAngles> views = exposure_views();
  REQUIRE(views.size() == size_t(kExposureLongitudes * kExposureLatitudes));
  const double deg = std::acos(-1.0) / 180;
  double lo = 90, hi = -90;
  for (const ViewAngles& v : views) {
    lo = std::min(lo, v.phi / deg);
    hi = std::max(hi, v.phi / deg);
    CHECK(v.theta > -std::acos(-1.0));
    CHECK(v.theta <= std::acos(-1.0));
  }
  CHECK(lo == Approx(kDefaultElevationMin));
  CHECK(hi == Approx(kDefaultElevationMax));
}

TEST_CASE("exposure equals its plain oracle for every weighting") {
  const Mesh mesh = make_bumpy_sphere(3);
  const ViewFrame frame = frame_mesh(mesh, UpAxis::Z);  // a turned frame too
  const std::vector<float> normals = exposure_normals(mesh);
  for (ExposureWeighting w : {ExposureWeighting{true, true}, ExposureWeighting{true, false},
                              ExposureWeighting{false, true}, ExposureWeighting{false, false}}) {
    const std::vector<double> fast = exposure_cpu(mesh, normals, frame, exposure_views(), w, coarse());
    const std::vector<double> plain = exposure_plain_cpu(mesh, normals, frame, exposure_views(), w, coarse());
    REQUIRE(fast.size() == plain.size());
    double worst = 0;
    for (size_t i = 0; i < fast.size(); ++i) worst = std::max(worst, std::fabs(fast[i] - plain[i]));
    INFO("facing " << w.facing << " centre " << w.centre);
    CHECK(max_of(plain) > 0.1);
    CHECK(worst <= 1e-6 * max_of(plain));  // float weights against double ones
  }
}

TEST_CASE("exposure is the same on any thread count") {
  const Mesh mesh = make_bumpy_sphere(3);
  const std::vector<double> one = exposure(mesh, {}, 1);
  CHECK(one == exposure(mesh, {}, 3));
  CHECK(one == exposure(mesh, {}, 8));
}

TEST_CASE("a sphere hidden inside another gets no exposure") {
  const Mesh outer = make_sphere(1.0, 3);
  const Mesh inner = make_sphere(0.5, 3);
  const Mesh both = joined(outer, inner);
  const std::vector<double> e = exposure(both, {true, false});
  double inner_max = 0, outer_max = 0;
  for (size_t i = 0; i < both.vertex_count(); ++i)
    (i < outer.vertex_count() ? outer_max : inner_max) = std::max(i < outer.vertex_count() ? outer_max : inner_max, e[i]);
  CHECK(inner_max == 0.0);
  // A point of a sphere faces some of the views squarely and the rest at a slant or not at all.
  CHECK(outer_max > 0.2);
  // Alone, the same inner sphere is seen as well as the outer one.
  CHECK(max_of(exposure(inner, {true, false})) == Approx(outer_max).epsilon(0.05));
}

TEST_CASE("views from above never see a cube's bottom and see its top at the band's sine") {
  const Mesh cube = make_cube(8);
  const std::vector<double> e = exposure(cube, {true, false});
  double bottom = 0, top_centre = -1;
  for (size_t i = 0; i < cube.vertex_count(); ++i) {
    const float* p = &cube.positions[3 * i];
    // The bottom face inside its edges (the edges' normals lean out to the sides).
    if (p[1] == -1.0f && std::fabs(p[0]) < 1.0f && std::fabs(p[2]) < 1.0f) bottom = std::max(bottom, e[i]);
    if (p[1] == 1.0f && p[0] == 0.0f && p[2] == 0.0f) top_centre = e[i];
  }
  CHECK(bottom == 0.0);
  // The top's normal is +y: seen in every view, facing = sin(phi), the mean of sin 10, 20, 30 degrees.
  const double deg = std::acos(-1.0) / 180;
  CHECK(top_centre == Approx((std::sin(10 * deg) + std::sin(20 * deg) + std::sin(30 * deg)) / 3).epsilon(1e-5));
}

TEST_CASE("the centre bias favours the middle of a long bar over its ends") {
  // A bar 8 long along x: in every view its ends lie far from the centre of the frame.
  Mesh bar = make_cube(6);
  for (size_t i = 0; i < bar.vertex_count(); ++i) bar.positions[3 * i] *= 8;
  const std::vector<double> e = exposure(bar, {false, true});
  double middle = 0, end = 0;
  for (size_t i = 0; i < bar.vertex_count(); ++i) {
    const float* p = &bar.positions[3 * i];
    if (p[1] != 1.0f) continue;  // the top face, seen in every view
    if (std::fabs(p[0]) < 1.5f) middle = std::max(middle, e[i]);
    if (std::fabs(p[0]) > 7.0f) end = std::max(end, e[i]);
  }
  CHECK(middle > 0.5);
  CHECK(end < 0.5 * middle);
}
