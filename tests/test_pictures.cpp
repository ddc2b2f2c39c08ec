// Pictures a person can read: the colour scale, the colour bar and title, --up, --best,
// --color-range, a saliency PLY reusing its saliency, the font.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <unistd.h>

#include <stb/stb_image.h>  // implemented in test_render.cpp

#include "core/colormap.h"
#include "core/synthetic.h"
#include "meshsal/meshsal.h"
#include "saliency/saliency.h"
#include "view/camera.h"
#include "view/legend.h"
#include "view/picture.h"
#include "test_util.h"

using namespace meshsal;

namespace {
const double kPi = 3.14159265358979323846;

struct PicDir {
  std::string path;
  PicDir() {
    char tmpl[] = "/tmp/meshsal_pictures_XXXXXX";
    const char* d = mkdtemp(tmpl);
    REQUIRE(d != nullptr);
    path = d;
  }
  ~PicDir() {
    std::error_code ec;
    std::filesystem::remove_all(path, ec);
  }
};

Image load_png(const std::string& path) {
  int w = 0, h = 0, c = 0;
  unsigned char* data = stbi_load(path.c_str(), &w, &h, &c, 3);
  REQUIRE(data != nullptr);
  Image img;
  img.width = w;
  img.height = h;
  img.rgb.assign(data, data + size_t(w) * size_t(h) * 3);
  stbi_image_free(data);
  return img;
}

// Position t on the colour scale of a (possibly shaded) colour: nearest chromaticity.
double scale_t(const uint8_t* p) {
  double sum = double(p[0]) + p[1] + p[2] + 1e-9, best = 1e9, best_t = 0;
  for (int k = 0; k <= 200; ++k) {
    uint8_t c[3];
    colormap_rgb(k / 200.0, c);
    double cs = double(c[0]) + c[1] + c[2] + 1e-9, e = 0;
    for (int j = 0; j < 3; ++j) e += std::pow(p[j] / sum - c[j] / cs, 2);
    if (e < best) {
      best = e;
      best_t = k / 200.0;
    }
  }
  return best_t;
}

bool same_rgb(const uint8_t* a, const uint8_t* b) { return a[0] == b[0] && a[1] == b[1] && a[2] == b[2]; }

int cli(const std::string& args, std::string* out = nullptr) {
  std::string file = "/tmp/meshsal_pictures_cli_" + std::to_string(getpid()) + ".txt";
  int rc = std::system((std::string(MESHSAL_CLI) + " " + args + " > " + file + " 2>&1").c_str());
  std::ifstream in(file);
  std::stringstream ss;
  ss << in.rdbuf();
  if (out) *out = ss.str();
  std::remove(file.c_str());
  return WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
}

// The row of a colour bar: a run of at least `min_len` pixels starting with the scale's low
// end and ending with its high end, t never falling. Returns the row or -1.
int find_colour_bar(const Image& img, int min_len, int* x0 = nullptr, int* x1 = nullptr) {
  uint8_t lo[3], hi[3];
  colormap_rgb(0, lo);
  colormap_rgb(1, hi);
  for (int y = img.height - 1; y >= 0; --y) {
    int start = -1;
    for (int x = 0; x < img.width; ++x) {
      if (same_rgb(img.at(x, y), lo) && start < 0) start = x;
      if (start >= 0 && same_rgb(img.at(x, y), hi) && x - start + 1 >= min_len) {
        bool rising = true;
        for (int k = start + 4; k <= x && rising; k += 4) rising = scale_t(img.at(k, y)) + 0.03 >= scale_t(img.at(k - 4, y));
        if (!rising) break;
        if (x0) *x0 = start;
        if (x1) *x1 = x;
        return y;
      }
    }
  }
  return -1;
}

// Bounding box of the non-white pixels in rows [y0, y1).
void ink_box(const Image& img, int y0, int y1, int* bx0, int* by0, int* bx1, int* by1) {
  *bx0 = img.width, *by0 = img.height, *bx1 = -1, *by1 = -1;
  for (int y = y0; y < y1; ++y)
    for (int x = 0; x < img.width; ++x) {
      const uint8_t* p = img.at(x, y);
      if (p[0] < 250 || p[1] < 250 || p[2] < 250) {
        *bx0 = std::min(*bx0, x), *bx1 = std::max(*bx1, x);
        *by0 = std::min(*by0, y), *by1 = std::max(*by1, y);
      }
    }
}

// A square pyramid, apex on +z (height 3, base 1 x 1 at z = 0): upright only when z is up.
Mesh z_up_pyramid() {
  std::vector<float> p{-0.5f, -0.5f, 0, 0.5f, -0.5f, 0, 0.5f, 0.5f, 0, -0.5f, 0.5f, 0, 0, 0, 3};
  std::vector<uint32_t> t{0, 2, 1, 0, 3, 2, 0, 1, 4, 1, 2, 4, 2, 3, 4, 3, 0, 4};
  return make_mesh(p.data(), 5, t.data(), t.size());
}
}  // namespace

TEST_CASE("pictures: the colour scale runs from a clear blue to dark red; --color-range values and percentiles", "[view]") {
  uint8_t c[3];
  colormap_rgb(0, c);
  CHECK(int(c[2]) > 200);  // blue, not Turbo's near-black end
  CHECK(int(c[0]) < 100);
  colormap_rgb(1, c);
  CHECK(int(c[0]) > 140);
  CHECK(int(c[2]) < 20);

  ColorRange r = parse_color_range("5%,99%");
  CHECK(r.lo == 5);
  CHECK(r.hi == 99);
  CHECK(r.lo_percentile);
  CHECK(r.hi_percentile);
  r = parse_color_range("0,0.5");
  CHECK(!r.lo_percentile);
  CHECK(r.hi == 0.5);
  CHECK_THROWS_WITH(parse_color_range("1,0.5"), Catch::Contains("LO must be below HI"));
  CHECK_THROWS_WITH(parse_color_range("0,120%"), Catch::Contains("percentile must be in [0, 100]"));
  CHECK_THROWS_WITH(parse_color_range("nan,1"), Catch::Contains("--color-range must be LO,HI"));
  CHECK_THROWS_WITH(parse_color_range("1"), Catch::Contains("--color-range must be LO,HI"));

  std::vector<double> v(101);
  for (int i = 0; i <= 100; ++i) v[size_t(i)] = i * 0.01;
  ColorLimits l = colour_limits(v, {});
  CHECK(l.lo == 0);
  CHECK(l.hi == Approx(1.0));
  l = colour_limits(v, {}, parse_color_range("10%,90%"));
  CHECK(l.lo == Approx(0.1));
  CHECK(l.hi == Approx(0.9));
  l = colour_limits(v, {}, parse_color_range("10%,0.5"));
  CHECK(l.hi == 0.5);
  // The square-root position: a quarter of the way up the values is half way up the colours.
  CHECK(colour_position(0.25, ColorLimits{0, 1}) == Approx(0.5));
  CHECK(colour_position(-1, ColorLimits{0, 1}) == 0);
  CHECK(colour_position(2, ColorLimits{0, 1}) == 1);
  // Beyond the ends: clamped to the end colours.
  std::vector<uint8_t> rgb = colormap_values(v, {}, ColorLimits{0.2, 0.4});
  uint8_t lo[3], hi[3];
  colormap_rgb(0, lo);
  colormap_rgb(1, hi);
  CHECK(same_rgb(&rgb[3 * 10], lo));
  CHECK(same_rgb(&rgb[3 * 90], hi));
}

TEST_CASE("pictures: the demo's unique feature is hotter than its repeated bumps in the PNG itself", "[view]") {
  std::vector<uint8_t> feature, bumps;
  Mesh mesh = make_bumpy_sphere(5, &feature, &bumps);
  SaliencyOptions so;
  so.backend = Backend::Cpu;
  SaliencyResult s = compute_saliency(mesh, so);
  // Look straight at the feature's centroid: it sits in the middle of the picture.
  double c[3] = {0, 0, 0};
  size_t n = 0;
  for (size_t v = 0; v < mesh.vertex_count(); ++v)
    if (feature[v]) {
      for (int k = 0; k < 3; ++k) c[k] += mesh.positions[3 * v + k];
      ++n;
    }
  REQUIRE(n > 0);
  ViewAngles view = direction_angles(c);
  RenderStyle style;
  style.size = 400;
  PicDir dir;
  write_png(dir.path + "/demo.png", titled_view(mesh, &s.saliency, view, style, "demo", "saliency"));
  Image img = load_png(dir.path + "/demo.png");
  const int top = title_height(text_size_for(400), 2);
  // The feature (about 0.1 of the sphere's radius across) at the centre; bumps in a ring
  // between 0.45 and 0.8 of the radius around it.
  double hot = 0, cool = 0, nh = 0, nc = 0;
  for (int y = 0; y < 400; ++y)
    for (int x = 0; x < 400; ++x) {
      const double r = std::hypot(x + 0.5 - 200, y + 0.5 - 200) / (200 / style.margin);
      const double t = scale_t(img.at(x, top + y));
      if (r < 0.05) hot += t, nh += 1;
      if (r > 0.45 && r < 0.8) cool += t, nc += 1;
    }
  REQUIRE(nh > 20);
  REQUIRE(nc > 1000);
  hot /= nh;
  cool /= nc;
  INFO("feature " << hot << ", bumps " << cool);
  CHECK(hot > 0.7);
  CHECK(cool < 0.3);
  CHECK(hot - cool > 0.5);
  // The picture carries its colour bar, under the mesh, with values (dark text) under it.
  int x0 = 0, x1 = 0;
  const int bar = find_colour_bar(img, 200, &x0, &x1);
  REQUIRE(bar > top + 400);
  int ink = 0;
  for (int y = bar + 1; y < std::min(img.height, bar + 30); ++y)
    for (int x = x0; x <= x1; ++x) ink += img.at(x, y)[0] < 80 && img.at(x, y)[1] < 80 && img.at(x, y)[2] < 80;
  CHECK(ink > 30);
  // Title text above the mesh.
  int tx0, ty0, tx1, ty1;
  ink_box(img, 0, top, &tx0, &ty0, &tx1, &ty1);
  CHECK(tx1 - tx0 > 150);
}

TEST_CASE("pictures: --up z turns a z-up mesh upright, --best renders the best view", "[view]") {
  PicDir dir;
  Mesh pyr = z_up_pyramid();
  write_obj(dir.path + "/pyr.obj", pyr);
  // Shape in the picture body (below the two title lines) of `render --grey`.
  auto shape = [&](const std::string& up, double* aspect, double* top_over_bottom) {
    std::string out;
    REQUIRE(cli("render " + dir.path + "/pyr.obj --grey --size 300 --theta 20 --phi 5 --up " + up + " -o " +
                    dir.path + "/p.png", &out) == 0);
    Image img = load_png(dir.path + "/p.png");
    const int top = title_height(text_size_for(300), 1);
    int x0, y0, x1, y1;
    ink_box(img, top, img.height, &x0, &y0, &x1, &y1);
    *aspect = double(y1 - y0) / double(x1 - x0);
    auto width_at = [&](int y) {
      int a = img.width, b = -1;
      for (int x = 0; x < img.width; ++x)
        if (img.at(x, y)[0] < 250) a = std::min(a, x), b = std::max(b, x);
      return b - a;
    };
    *top_over_bottom = double(width_at(y0 + (y1 - y0) / 5)) / double(width_at(y1 - (y1 - y0) / 10));
  };
  double aspect = 0, ratio = 0;
  shape("z", &aspect, &ratio);
  CHECK(aspect > 2);   // tall
  CHECK(ratio < 0.5);  // apex on top
  shape("y", &aspect, &ratio);
  CHECK(aspect < 1);  // y up: the pyramid lies on its side
  shape("-z", &aspect, &ratio);
  CHECK(aspect > 2);
  CHECK(ratio > 2);  // upside down

  // --best: a sphere whose saliency is max(0, x) is best seen from +x (theta 90 with y up).
  Mesh s = make_sphere(1.0, 3);
  std::vector<double> q(s.vertex_count());
  for (size_t i = 0; i < q.size(); ++i) q[i] = std::max(0.0, double(s.positions[3 * i]));
  write_ply(dir.path + "/s.ply", s, {{"quality", &q}});
  std::string out;
  REQUIRE(cli("render " + dir.path + "/s.ply --best --backend cpu --size 64 -o " + dir.path + "/b.png", &out) == 0);
  INFO(out);
  size_t at = out.find("best view: theta ");
  REQUIRE(at != std::string::npos);
  CHECK(std::fabs(std::strtod(out.c_str() + at + 17, nullptr) - 90) < 15);
  CHECK(cli("render " + dir.path + "/s.ply --best --theta 10 -o " + dir.path + "/b.png", &out) == 2);
}

TEST_CASE("pictures: a saliency PLY given as input reuses its own saliency and says so", "[view]") {
  PicDir dir;
  Mesh s = make_sphere(1.0, 3);
  std::vector<double> q(s.vertex_count());
  for (size_t i = 0; i < q.size(); ++i) q[i] = std::max(0.0, double(s.positions[3 * i]));
  write_ply(dir.path + "/s.ply", s, {{"quality", &q}});
  std::string out;
  REQUIRE(cli("render " + dir.path + "/s.ply --theta 90 --size 320 -o " + dir.path + "/r.png", &out) == 0);
  CHECK(out.find("s.ply: using its own saliency") != std::string::npos);
  Image img = load_png(dir.path + "/r.png");
  const int top = title_height(text_size_for(320), 2);
  CHECK(scale_t(img.at(160, top + 160)) > 0.8);  // max(0, x) faces the viewer: hot
  REQUIRE(cli("viewpoint " + dir.path + "/s.ply --backend cpu --resolution 64 --restarts 2", &out) == 0);
  CHECK(out.find("\"score_source\": \"" + dir.path + "/s.ply\"") != std::string::npos);
  CHECK(out.find("using its own saliency") != std::string::npos);

  // --color-range 0,0.25: everything above 0.25 is the top colour; bad ranges are usage errors.
  REQUIRE(cli("render " + dir.path + "/s.ply --theta 90 --size 320 --color-range 0,0.25 -o " + dir.path + "/c.png",
              &out) == 0);
  img = load_png(dir.path + "/c.png");
  CHECK(scale_t(img.at(160 - 70, top + 160)) > 0.9);  // x about 0.9 there: clipped at the top
  CHECK(cli("render " + dir.path + "/s.ply --color-range 2,1 -o " + dir.path + "/c.png", &out) == 2);
  CHECK(out.find("--color-range: LO must be below HI") != std::string::npos);
  // A missing font is a one-line error naming it, and no picture.
  CHECK(cli("render " + dir.path + "/s.ply -o " + dir.path + "/f.png", &out) == 0);
  CHECK(std::system(("MESHSAL_FONT=/nonexistent/font.ttf " + std::string(MESHSAL_CLI) + " render " + dir.path +
                     "/s.ply -o " + dir.path + "/g.png > /dev/null 2>&1").c_str()) != 0);
  CHECK(!std::filesystem::exists(dir.path + "/g.png"));
  setenv("MESHSAL_FONT", "/nonexistent/font.ttf", 1);
  CHECK_THROWS_WITH(titled_view(s, &q, {0, 0}, RenderStyle{}, "s", "saliency"),
                    Catch::Contains("/nonexistent/font.ttf: no usable TrueType font") &&
                        Catch::Contains("fonts-dejavu-core"));
  unsetenv("MESHSAL_FONT");
}
