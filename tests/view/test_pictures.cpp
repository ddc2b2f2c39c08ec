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

#include "io/colormap.h"
#include "cli/synthetic.h"
#include "meshsal/meshsal.h"
#include "saliency/saliency.h"
#include "view/camera.h"
#include "view/legend.h"
#include "view/map_picture.h"
#include "view/picture.h"
#include "view/render.h"
#include "view/text.h"
#include "view/viewpoint.h"
#include "cli_run.h"
#include "png_check.h"
#include "test_util.h"

using namespace meshsal;
using meshsal_test::CliRun;
using meshsal_test::colormap_position;
using meshsal_test::PictureDir;
using meshsal_test::run_cli_merged;
using meshsal_test::read_png;

namespace {
const double kPi = 3.14159265358979323846;

bool same_rgb(const uint8_t* a, const uint8_t* b) { return a[0] == b[0] && a[1] == b[1] && a[2] == b[2]; }

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
        for (int k = start + 4; k <= x && rising; k += 4) rising = colormap_position(img.at(k, y)) + 0.03 >= colormap_position(img.at(k - 4, y));
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

TEST_CASE("pictures: the colour scale runs from a clear blue to dark red, --color-range values and percentiles", "[view]") {
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
  CHECK_THROWS_WITH(parse_color_range("nan,1"), Catch::Contains("color range must be LO,HI"));
  CHECK_THROWS_WITH(parse_color_range("1"), Catch::Contains("color range must be LO,HI"));

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
  PictureDir dir;
  write_png(dir.path + "/demo.png", titled_view(mesh, &s.saliency, view, style, "demo", "saliency"));
  Image img = read_png(dir.path + "/demo.png");
  const int top = title_height(text_size_for(400), 2);
  // The feature (about 0.1 of the sphere's radius across) at the centre; bumps in a ring
  // between 0.45 and 0.8 of the radius around it.
  double hot = 0, cool = 0, nh = 0, nc = 0;
  for (int y = 0; y < 400; ++y)
    for (int x = 0; x < 400; ++x) {
      const double r = std::hypot(x + 0.5 - 200, y + 0.5 - 200) / (200 / style.margin);
      const double t = colormap_position(img.at(x, top + y));
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
  PictureDir dir;
  Mesh pyr = z_up_pyramid();
  write_obj(dir.path + "/pyr.obj", pyr);
  // Shape in the picture body (below the two title lines) of `render --grey`.
  auto shape = [&](const std::string& up, double* aspect, double* top_over_bottom) {
    CliRun r;
    REQUIRE((r = run_cli_merged("render " + dir.path + "/pyr.obj --grey --size 300 --theta 20 --phi 5 --up " + up + " -o " +
                    dir.path + "/p.png")).rc == 0);
    Image img = read_png(dir.path + "/p.png");
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
  CliRun r;
  REQUIRE((r = run_cli_merged("render " + dir.path + "/s.ply --best --backend cpu --size 64 -o " + dir.path + "/b.png")).rc == 0);
  INFO(r.out);
  size_t at = r.out.find("best view: theta ");
  REQUIRE(at != std::string::npos);
  CHECK(std::fabs(std::strtod(r.out.c_str() + at + 17, nullptr) - 90) < 15);
  CHECK((r = run_cli_merged("render " + dir.path + "/s.ply --best --theta 10 -o " + dir.path + "/b.png")).rc == 2);
}

TEST_CASE("pictures: a saliency PLY given as input reuses its own saliency and says so", "[view]") {
  PictureDir dir;
  Mesh s = make_sphere(1.0, 3);
  std::vector<double> q(s.vertex_count());
  for (size_t i = 0; i < q.size(); ++i) q[i] = std::max(0.0, double(s.positions[3 * i]));
  write_ply(dir.path + "/s.ply", s, {{"quality", &q}});
  CliRun r;
  REQUIRE((r = run_cli_merged("render " + dir.path + "/s.ply --theta 90 --size 320 -o " + dir.path + "/r.png")).rc == 0);
  CHECK(r.out.find("s.ply: using its own saliency") != std::string::npos);
  Image img = read_png(dir.path + "/r.png");
  const int top = title_height(text_size_for(320), 2);
  CHECK(colormap_position(img.at(160, top + 160)) > 0.8);  // max(0, x) faces the viewer: hot
  REQUIRE((r = run_cli_merged("viewpoint " + dir.path + "/s.ply --backend cpu --resolution 64 --restarts 2")).rc == 0);
  CHECK(r.out.find("\"score_source\": \"" + dir.path + "/s.ply\"") != std::string::npos);
  CHECK(r.out.find("using its own saliency") != std::string::npos);

  // --color-range 0,0.25: everything above 0.25 is the top colour; bad ranges are usage errors.
  REQUIRE((r = run_cli_merged("render " + dir.path + "/s.ply --theta 90 --size 320 --color-range 0,0.25 -o " + dir.path + "/c.png")).rc == 0);
  img = read_png(dir.path + "/c.png");
  CHECK(colormap_position(img.at(160 - 70, top + 160)) > 0.9);  // x about 0.9 there: clipped at the top
  CHECK((r = run_cli_merged("render " + dir.path + "/s.ply --color-range 2,1 -o " + dir.path + "/c.png")).rc == 2);
  CHECK(r.out.find("--color-range: LO must be below HI") != std::string::npos);
  // A missing font is a one-line error naming it, and no picture.
  CHECK((r = run_cli_merged("render " + dir.path + "/s.ply -o " + dir.path + "/f.png")).rc == 0);
  CHECK(std::system(("MESHSAL_FONT=/nonexistent/font.ttf " + std::string(MESHSAL_CLI) + " render " + dir.path +
                     "/s.ply -o " + dir.path + "/g.png > /dev/null 2>&1").c_str()) != 0);
  CHECK(!std::filesystem::exists(dir.path + "/g.png"));
  setenv("MESHSAL_FONT", "/nonexistent/font.ttf", 1);
  CHECK_THROWS_WITH(titled_view(s, &q, {0, 0}, RenderStyle{}, "s", "saliency"),
                    Catch::Contains("/nonexistent/font.ttf: no usable TrueType font") &&
                        Catch::Contains("fonts-dejavu-core"));
  unsetenv("MESHSAL_FONT");
}

namespace {
const uint8_t kInk[3] = {20, 20, 20};  // the pictures' text and tick colour

// True when `text`, drawn alone on white at (x, y) as the pictures draw it, is exactly what
// the picture holds in the text's line box (so the label is there, and only it).
bool text_at(const Image& img, int x, int y, const std::string& text, double px) {
  Image alone(img.width, img.height);
  draw_text(alone, x, y, text, px, kInk);
  const int line = int(std::lround(px * 1.25)), w = text_width(text, px);
  int inked = 0, differ = 0;
  for (int yy = y; yy < std::min(img.height, y + line); ++yy)
    for (int xx = std::max(0, x - 1); xx < std::min(img.width, x + w + 2); ++xx) {
      inked += alone.at(xx, yy)[0] < 128;
      differ += !same_rgb(alone.at(xx, yy), img.at(xx, yy));
    }
  INFO("'" << text << "' at " << x << "," << y << ": " << inked << " ink pixels, " << differ << " differ");
  return inked > 10 && differ == 0;
}

// Dark pixels (text, ticks) in the box [x0, x1) x [y0, y1).
int dark_pixels(const Image& img, int x0, int y0, int x1, int y1) {
  int n = 0;
  for (int y = std::max(0, y0); y < std::min(img.height, y1); ++y)
    for (int x = std::max(0, x0); x < std::min(img.width, x1); ++x)
      n += img.at(x, y)[0] < 100 && img.at(x, y)[1] < 100 && img.at(x, y)[2] < 100;
  return n;
}

// The columns [x0, x1) of an image.
Image columns(const Image& img, int x0, int x1) {
  Image out(x1 - x0, img.height);
  for (int y = 0; y < img.height; ++y) std::copy(img.at(x0, y), img.at(x1, y), out.at(0, y));
  return out;
}

bool is_white(const uint8_t* p) { return p[0] == 255 && p[1] == 255 && p[2] == 255; }
}  // namespace

TEST_CASE("pictures: render --compare labels each panel, colours the simplified ones by distance, with colour bars", "[view]") {
  PictureDir dir;
  // The original: a sphere with saliency max(0, x). "plain": its +x cap pushed out by 15%
  // (far from the original there, on it elsewhere); "saliency-weighted": the sphere itself.
  Mesh original = make_sphere(1.0, 3);
  std::vector<double> q(original.vertex_count());
  Mesh plain = original;
  for (size_t i = 0; i < q.size(); ++i) {
    q[i] = std::max(0.0, double(original.positions[3 * i]));
    if (original.positions[3 * i] > 0.3f)
      for (int k = 0; k < 3; ++k) plain.positions[3 * i + k] *= 1.15f;
  }
  write_ply(dir.path + "/o.ply", original, {{"quality", &q}});
  write_obj(dir.path + "/plain.obj", plain);
  write_obj(dir.path + "/salient.obj", original);
  CliRun r;
  REQUIRE((r = run_cli_merged("render " + dir.path + "/o.ply --compare " + dir.path + "/plain.obj " + dir.path +
                  "/salient.obj --size 240 --theta 0 --phi 0 -o " + dir.path + "/c.png")).rc == 0);
  INFO(r.out);
  const Image img = read_png(dir.path + "/c.png");
  const int size = 240, gap = 4;
  REQUIRE(img.width == 3 * size + 2 * gap);
  const double px = text_size_for(size);
  const int pad = int(std::lround(px * 0.4)), line = int(std::lround(px * 1.25)), top = pad + 4 * line;
  const size_t faces = original.triangle_count();

  // The title line, and each panel's label: its name and face count, then what colours it.
  CHECK(text_at(img, pad, pad, "o.ply   theta 0.0°  phi 0.0°  (y up)", px));
  CHECK(text_at(img, pad, pad + line, "original: " + std::to_string(faces) + " faces", px));
  CHECK(text_at(img, pad, pad + 2 * line, "coloured by saliency", px));
  // Each simplified panel is named by its file.
  CHECK(text_at(img, size + gap + pad, pad + line, "plain.obj: " + std::to_string(faces) + " faces", px));
  CHECK(text_at(img, 2 * (size + gap) + pad, pad + line, "salient.obj: " + std::to_string(faces) + " faces", px));
  // RMS and Hausdorff, then the salient-region error under the simplified panels: the
  // weighted one is the original itself (0%), the plain one is off by a few % on its
  // salient (+x) side.
  CHECK(text_at(img, 2 * (size + gap) + pad, pad + 2 * line, "RMS 0%, Hausdorff 0%", px));
  CHECK(text_at(img, 2 * (size + gap) + pad, pad + 3 * line, "salient-region error 0%", px));
  CHECK(dark_pixels(img, size + gap, pad + 2 * line, 2 * size + gap, pad + 4 * line) > 100);
  CHECK(!text_at(img, size + gap + pad, pad + 2 * line, "RMS 0%, Hausdorff 0%", px));
  CHECK(!text_at(img, size + gap + pad, pad + 3 * line, "salient-region error 0%", px));

  // Panel bodies, looking from +z: +x on the right. Colour positions t (0 blue .. 1 red).
  const int cy = top + size / 2;
  const double R = size / 2 / 1.05;  // the sphere's radius in pixels (framed with 5% margin)
  auto t_at = [&](int panel, double fx, double fy) {
    const uint8_t* p = img.at(panel * (size + gap) + size / 2 + int(fx * R), cy - int(fy * R));
    REQUIRE(!is_white(p));
    return colormap_position(p);
  };
  CHECK(t_at(0, 0.7, 0) > 0.75);   // original by saliency: max(0, x) hot on the right
  CHECK(t_at(0, -0.7, 0) < 0.1);   // and cold on the left
  CHECK(t_at(1, 0.7, 0) > 0.8);    // plain by distance: its pushed-out cap is the farthest
  CHECK(t_at(1, 0.7, 0.3) > 0.8);
  CHECK(t_at(1, -0.7, 0) < 0.05);  // on the original elsewhere: distance 0, blue
  CHECK(t_at(1, 0, -0.5) < 0.05);
  for (double fx : {-0.6, -0.3, 0.0, 0.3, 0.6})
    for (double fy : {-0.5, 0.0, 0.5}) CHECK(t_at(2, fx, fy) < 0.05);  // the original itself: 0 everywhere

  // Colour bars under the panels: saliency under the original, distance under both others.
  int x0 = 0, x1 = 0;
  const int bar = find_colour_bar(columns(img, size, img.width), 2 * size - 40, &x0, &x1);
  REQUIRE(bar > top + size);
  x0 += size, x1 += size;
  CHECK(x0 >= size + gap);
  CHECK(x0 < size + gap + 20);
  CHECK(x1 > 3 * size - 10);
  CHECK(dark_pixels(img, x0, bar + 1, x1 + 1, bar + 4 + line) > 60);  // ticks and their values
  int s0 = 0, s1 = 0;
  const int sal_bar = find_colour_bar(columns(img, 0, size), size / 2, &s0, &s1);
  CHECK(sal_bar == bar);
  CHECK(s1 - s0 > size - 6 * pad);
  CHECK(text_at(img, 2 * pad, top + size + pad, "saliency, square-root scale", px));
  CHECK(text_at(img, size + gap + 2 * pad, top + size + pad,
                "distance to the original (% of the diagonal), square-root scale", px));
}

TEST_CASE("pictures: the view map has its axes' ticks, a colour bar, its markers and their legend", "[view]") {
  ViewMap map;
  map.views = fibonacci_directions(600);
  for (const ViewAngles& a : map.views) {
    double d[3];
    view_direction(a, d);
    map.U.push_back(1 + d[0]);  // hottest from +x (theta 90), coldest from -x (theta -90)
  }
  map.best = size_t(std::max_element(map.U.begin(), map.U.end()) - map.U.begin());
  // The ring on the hottest colour, the cross on the coldest: each must show on either.
  const ViewAngles ring{kPi / 2, 0}, cross{-kPi / 2, 0.2};
  const int width = 720;
  PictureDir dir;
  write_png(dir.path + "/map.png", view_map_picture(map, width, ring, "exhaustive maximum", cross,
                                                    "optimiser's result", "a title"));
  const Image img = read_png(dir.path + "/map.png");

  // Find the plot (with both markers, as render_view_map draws them) in the picture.
  const Image plot = render_view_map(map, width, &ring, &cross);
  int left = -1, top = -1;
  for (int y = 0; y + plot.height <= img.height && left < 0; ++y)
    for (int x = 0; x + plot.width <= img.width; ++x)
      if (std::equal(plot.at(0, 0), plot.at(0, 0) + 3 * plot.width, img.at(x, y)) &&
          std::equal(plot.at(0, plot.height - 1), plot.at(0, plot.height - 1) + 3 * plot.width,
                     img.at(x, y + plot.height - 1))) {
        left = x, top = y;
        break;
      }
  REQUIRE(left > 0);
  for (int y = 0; y < plot.height; ++y) REQUIRE(std::equal(plot.at(0, y), plot.at(0, y) + 3 * plot.width, img.at(left, top + y)));

  // Markers: a white ring with a black rim on the red maximum, a black cross edged in white on
  // the blue minimum.
  const Image bare = render_view_map(map, width, nullptr, nullptr);
  const int r = std::max(4, width / 100);
  int cx, cy;
  view_map_pixel(ring, width, &cx, &cy);
  CHECK(colormap_position(bare.at(cx + 2, cy + 2)) > 0.9);  // beside the grid lines through (90, 0)
  int white = 0, black = 0, on_ring = 0, rim = 0;
  for (int dy = -r - 2; dy <= r + 2; ++dy)
    for (int dx = -r - 2; dx <= r + 2; ++dx) {
      const double dd = std::hypot(dx, dy) - r;
      const uint8_t* p = img.at(left + cx + dx, top + cy + dy);
      if (std::fabs(dd) < 1.0) on_ring++, white += p[0] == 255 && p[1] == 255 && p[2] == 255;
      if (dd >= 1.0 && dd < 2.0) rim++, black += p[0] == 0 && p[1] == 0 && p[2] == 0;
    }
  CHECK(white == on_ring);
  CHECK(black == rim);
  CHECK(colormap_position(img.at(left + cx + 2, top + cy + 2)) > 0.9);  // the maximum stays visible inside
  view_map_pixel(cross, width, &cx, &cy);
  CHECK(colormap_position(bare.at(cx + 3, cy + 3)) < 0.1);
  for (int k = -r; k <= r; ++k) {
    CHECK(img.at(left + cx + k, top + cy)[0] == 0);
    CHECK(img.at(left + cx, top + cy + k)[1] == 0);
    if (k == -1 || k == 0) continue;  // the vertical arm's black crosses the edges there
    CHECK(img.at(left + cx + k, top + cy - 2)[2] == 255);
    CHECK(img.at(left + cx + k, top + cy + 1)[2] == 255);
  }

  // Ticks: phi every 30 degrees left of the plot, theta every 60 below it, each with its value.
  const double px = text_size_for(width);
  int ticks = 0;
  for (int phi = 90; phi >= -90; phi -= 30) {
    int x, y;
    view_map_pixel({0, phi * kPi / 180}, width, &x, &y);
    y = phi == 90 ? 0 : phi == -90 ? plot.height - 1 : y;
    bool tick = true;
    for (int k = 1; k <= 6; ++k) tick &= same_rgb(img.at(left - k, top + y), kInk);
    ticks += tick;
    CHECK(dark_pixels(img, 0, top + y - int(px), left - 6, top + y + int(px)) > 15);  // "30°"
  }
  CHECK(ticks == 7);
  CHECK(!same_rgb(img.at(left - 3, top + plot.height / 4), kInk));  // none between (phi 45)
  ticks = 0;
  for (int theta = -180; theta <= 180; theta += 60) {
    const int x = theta == 180 ? plot.width - 1 : int(std::lround((theta + 180) / 360.0 * plot.width));
    bool tick = true;
    for (int k = 0; k < 6; ++k) tick &= same_rgb(img.at(left + x, top + plot.height + k), kInk);
    ticks += tick;
    CHECK(dark_pixels(img, left + x - int(px), top + plot.height + 6, left + x + int(px),
                      top + plot.height + 6 + int(px * 1.25)) > 15);  // "-120°"
  }
  CHECK(ticks == 7);
  CHECK(dark_pixels(img, 0, top + plot.height / 2 - int(px), left - 8 - text_width("-90°", px), top + plot.height / 2 + int(px)) > 20);  // "phi"

  // The colour bar of U below, with its values, spanning the plot.
  int x0 = 0, x1 = 0;
  const int bar = find_colour_bar(img, plot.width - 10, &x0, &x1);
  REQUIRE(bar > top + plot.height);
  CHECK(x0 == left);
  CHECK(dark_pixels(img, x0, bar + 1, x1 + 1, bar + 30) > 60);

  // The legend between the axes and the bar: each marker drawn on mid grey, then its label.
  int samples = 0;
  for (int y = top + plot.height + 6; y < bar; ++y)
    for (int x = left; x < left + 4; ++x) {
      const uint8_t* p = img.at(x, y);
      if (!(p[0] == 120 && p[1] == 120 && p[2] == 120)) continue;
      const uint8_t* above = img.at(x, y - 1);
      if (above[0] == 120 && above[1] == 120) continue;  // the top edge of a sample only
      // A sample: a square whose left column and top row are all mid grey (not a text pixel).
      const int side = 2 * int(px * 0.4) + 8;
      bool square = true;
      for (int k = 0; k < side; ++k) square &= img.at(x, y + k)[0] == 120 && img.at(x + k, y)[0] == 120;
      if (!square) continue;
      ++samples;
      // Inside the sample: white and black marker pixels; right of it: the label's text.
      int w = 0, b = 0;
      for (int yy = y; yy < y + side; ++yy)
        for (int xx = x; xx < x + side; ++xx) w += is_white(img.at(xx, yy)), b += img.at(xx, yy)[0] == 0;
      CHECK(w > 10);
      CHECK(b > 10);
      CHECK(dark_pixels(img, x + side, y, x + side + 200, y + side) > 100);
      break;
    }
  CHECK(samples == 2);
}
