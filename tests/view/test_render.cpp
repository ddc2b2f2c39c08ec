// Pictures: renderer coverage and colours, the view map, PNG files, and the two CLI commands.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <unistd.h>

#include "view/camera.h"
#include "io/colormap.h"
#include "meshsal/meshsal.h"
#include "io/png_image.h"
#include "view/render.h"
#include "view/legend.h"
#include "cli/render_demo.h"
#include "cli/synthetic.h"
#include "cli_run.h"
#include "json_check.h"
#include "png_check.h"
#include "test_util.h"

using namespace meshsal;
using meshsal_test::CliRun;
using meshsal_test::colormap_position;
using meshsal_test::colour_in_range;
using meshsal_test::pixel_counts;
using meshsal_test::PixelCounts;
using meshsal_test::json_number;
using meshsal_test::PictureDir;
using meshsal_test::run_cli_merged;
using meshsal_test::read_png;

namespace {
const double kPi = 3.14159265358979323846;

bool is_background(const uint8_t* p) { return p[0] == 255 && p[1] == 255 && p[2] == 255; }

}  // namespace

TEST_CASE("render: a sphere fills the picture (framed by its projected extent), centred", "[view]") {
  Mesh s = make_sphere(1.0, 4);
  ViewFrame frame = frame_mesh(s);
  RenderStyle style;
  style.size = 200;
  Image img = render_mesh(s, nullptr, frame, {0.6, 0.3}, style);
  REQUIRE(img.width == 200);
  REQUIRE(img.height == 200);
  REQUIRE(img.rgb.size() == size_t(200 * 200 * 3));
  double covered = 0, cx = 0, cy = 0;
  for (int y = 0; y < 200; ++y)
    for (int x = 0; x < 200; ++x)
      if (!is_background(img.at(x, y))) {
        covered += 1;
        cx += x + 0.5;
        cy += y + 0.5;
      }
  double r_px = 100.0 / style.margin;  // the sphere's outline spans the picture, less the margin
  CHECK(covered / (kPi * r_px * r_px) == Approx(1.0).margin(0.03));
  CHECK(cx / covered == Approx(100).margin(1.0));
  CHECK(cy / covered == Approx(100).margin(1.0));
  // Shading: the lit centre is brighter than the rim, and nothing is black.
  CHECK(int(img.at(100, 100)[0]) > int(img.at(100 + int(r_px) - 3, 100)[0]));
  CHECK(int(img.at(100, 100)[0]) > 150);
}

TEST_CASE("render: colours follow saliency (low blue, high red)", "[view]") {
  Mesh s = make_sphere(1.0, 4);
  std::vector<double> score(s.vertex_count());
  for (size_t i = 0; i < score.size(); ++i) score[i] = s.positions[3 * i];  // grows to the right (+x)
  std::vector<uint8_t> colours = score_colours(s, score);
  RenderStyle style;
  style.size = 160;
  Image img = render_mesh(s, &colours, frame_mesh(s), {0, 0}, style);  // from +z: +x is right
  // Mean colour-map position per column band over the covered pixels rises left to right.
  double band[4] = {0, 0, 0, 0}, count[4] = {0, 0, 0, 0};
  for (int y = 0; y < 160; ++y)
    for (int x = 0; x < 160; ++x) {
      const uint8_t* p = img.at(x, y);
      if (is_background(p)) continue;
      int b = std::min(3, std::max(0, (x - 4) * 4 / 152));  // the disc spans about x 4..156
      band[b] += colormap_position(p);
      count[b] += 1;
    }
  for (int b = 0; b < 4; ++b) {
    REQUIRE(count[b] > 50);
    band[b] /= count[b];
  }
  INFO("bands " << band[0] << " " << band[1] << " " << band[2] << " " << band[3]);
  CHECK(band[0] < 0.45);  // blue to cyan on the low side (x -1..-0.5: positions sqrt(0..0.25))
  CHECK(band[3] > 0.8);  // red on the high side
  CHECK(band[0] < band[1]);
  CHECK(band[1] < band[2]);
  CHECK(band[2] < band[3]);
  // The default scale is minimum to maximum, unclipped: one extreme vertex is the only red one.
  std::vector<double> one_hot(s.vertex_count(), 0.0);
  one_hot[0] = 1000.0;
  std::vector<uint8_t> c2 = score_colours(s, one_hot);
  CHECK(colormap_position(&c2[0]) > 0.95);
  CHECK(colormap_position(&c2[3]) < 0.05);
  CHECK(c2[3] == c2[6]);
}

TEST_CASE("render: view map, side by side and PNG round trip", "[view]") {
  ViewMap map;
  map.views = fibonacci_directions(800);
  for (const ViewAngles& a : map.views) {
    double d[3];
    view_direction(a, d);
    map.U.push_back(d[0]);  // hottest looking from +x: theta 90, phi 0
  }
  map.best = size_t(std::max_element(map.U.begin(), map.U.end()) - map.U.begin());
  ViewAngles hot{kPi / 2, 0};
  Image m = render_view_map(map, 360, &hot, nullptr);
  REQUIRE(m.width == 360);
  REQUIRE(m.height == 180);
  int x, y;
  view_map_pixel(hot, 360, &x, &y);
  CHECK(x == 270);
  CHECK(y == 90);
  const uint8_t* h = m.at(x + 2, y + 1);   // inside the ring
  const uint8_t* c = m.at(90 + 2, 90 + 1);  // theta -90: coldest
  CHECK(colormap_position(h) > 0.9);
  CHECK(colormap_position(c) < 0.1);
  const uint8_t* ring = m.at(x + std::max(4, 360 / 100), y);
  CHECK((ring[0] == 255 && ring[1] == 255 && ring[2] == 255));

  Mesh cube = make_cube(4);
  RenderStyle style;
  style.size = 64;
  style.edges = true;
  style.smooth = false;
  Image sbs = render_side_by_side({&cube, &cube, &cube}, {nullptr, nullptr, nullptr}, frame_mesh(cube),
                                  {0.5, 0.4}, style);
  CHECK(sbs.width == 3 * 64 + 2 * 4);
  CHECK(sbs.height == 64);
  // The three panels are identical renders.
  for (int yy = 0; yy < 64; ++yy)
    for (int xx = 0; xx < 64; ++xx) REQUIRE(std::equal(sbs.at(xx, yy), sbs.at(xx, yy) + 3, sbs.at(xx + 136, yy)));

  PictureDir tmp;
  const std::string& dir = tmp.path;
  write_png(dir + "/sbs.png", sbs);
  Image back = read_png(dir + "/sbs.png");
  CHECK(back.width == sbs.width);
  CHECK(back.height == sbs.height);
  CHECK(back.rgb == sbs.rgb);
  CHECK_THROWS_AS(write_png("/nonexistent-dir/x.png", sbs), Error);
  style.size = 8;
  CHECK_THROWS_AS(render_mesh(cube, nullptr, frame_mesh(cube), {0, 0}, style), Error);
}

TEST_CASE("render: demo pictures are written", "[view]") {
  std::vector<uint8_t> feature;
  Mesh mesh = make_bumpy_sphere(3, &feature);
  std::vector<double> sal(mesh.vertex_count());
  for (size_t i = 0; i < sal.size(); ++i) sal[i] = feature[i] ? 1.0 : 0.05;
  PictureDir tmp;
  const std::string& dir = tmp.path;
  DemoPictureOptions opt;
  opt.image_size = 256;
  opt.map_views = 400;
  std::vector<std::string> files = write_demo_pictures(mesh, sal, dir, &mesh, &mesh, opt);
  REQUIRE(files.size() == 3);
  // The best view: the model fills the middle of the picture in saliency colours, cold there
  // (all but the feature's one or two vertices have saliency 0.05 of the maximum).
  const Image best = read_png(files[0]);
  CHECK(best.width >= 256);  // the picture, or its title if wider
  CHECK(best.height > 256);  // title and colour bar
  const int cx = best.width / 2, cy = best.height / 2;
  const PixelCounts middle = pixel_counts(best, cx - 64, cy - 64, cx + 64, cy + 64);
  const int cold = colour_in_range(best, cx - 64, cy - 64, cx + 64, cy + 64, 0.0, 0.2);
  INFO("best: middle coloured " << middle.coloured << " of " << 128 * 128 << ", cold " << cold);
  CHECK(middle.coloured > 128 * 128 * 9 / 10);
  CHECK(cold > 128 * 128 * 3 / 4);
  // The view map: a plot in saliency colours with its axes (dark text and lines).
  const Image map = read_png(files[1]);
  CHECK(map.width > 720);
  const PixelCounts plot = pixel_counts(map);
  INFO("map: " << map.width << "x" << map.height << " coloured " << plot.coloured << " dark " << plot.dark);
  CHECK(plot.coloured > map.width * map.height / 3);
  CHECK(plot.dark > 500);
  // The comparison: three panels, each the model in saliency colours.
  const Image sbs = read_png(files[2]);
  CHECK(sbs.width == 3 * 256 + 8);
  for (int panel = 0; panel < 3; ++panel) {
    const PixelCounts c = pixel_counts(sbs, panel * 260, 0, panel * 260 + 256, sbs.height);
    INFO("panel " << panel << ": coloured " << c.coloured << ", not white " << c.not_white);
    CHECK(c.coloured > 256 * 256 / 4);
  }
}

TEST_CASE("cli: meshsal viewpoint prints JSON and writes pictures, render draws any view", "[view]") {
  PictureDir tmp;
  const std::string& dir = tmp.path;
  // A sphere whose saliency (PLY quality) is max(0, x): the best view looks from +x.
  Mesh s = make_sphere(1.0, 3);
  std::vector<double> q(s.vertex_count());
  for (size_t i = 0; i < q.size(); ++i) q[i] = std::max(0.0, double(s.positions[3 * i]));
  write_ply(dir + "/s.ply", s, {{"quality", &q}});
  CliRun cr;
  REQUIRE((cr = run_cli_merged("viewpoint " + dir + "/s.ply --saliency-from " + dir + "/s.ply --backend cpu --resolution 64 "
                  "--restarts 3 --views 150 -o " + dir + "/best.png --map " + dir + "/map.png --size 128")).rc == 0);
  INFO(cr.out);
  double d0 = 0;
  {
    size_t at = cr.out.find("\"direction\": [");
    REQUIRE(at != std::string::npos);
    d0 = std::strtod(cr.out.c_str() + at + 14, nullptr);
  }
  CHECK(d0 > 0.9);
  CHECK(json_number(cr.out, "views_evaluated") > 150);
  CHECK(json_number(cr.out, "visible_score") >= 0.98 * json_number(cr.out.substr(cr.out.find("\"exhaustive\"")), "visible_score"));
  CHECK(json_number(cr.out, "visible_fraction") > 0.5);
  // The best view looks from +x at the hot side: the middle of the picture is the model, hot.
  const Image best = read_png(dir + "/best.png");
  CHECK(best.width >= 128);  // at least the picture; the title may be wider
  {
    const int cx = best.width / 2, cy = best.height / 2;
    const int hot = colour_in_range(best, cx - 24, cy - 24, cx + 24, cy + 24, 0.75, 1.0);
    INFO("best.png " << best.width << "x" << best.height << ": hot " << hot << " of " << 48 * 48);
    CHECK(hot > 48 * 48 / 2);
  }
  const Image map = read_png(dir + "/map.png");
  CHECK(map.width > 720);  // the plot with its axes
  INFO("map.png coloured " << pixel_counts(map).coloured << " of " << map.width * map.height);
  CHECK(pixel_counts(map).coloured > map.width * map.height / 3);

  REQUIRE((cr = run_cli_merged("render " + dir + "/s.ply --saliency-from " + dir + "/s.ply --theta 90 --phi 0 --size 320 -o " +
                  dir + "/r.png")).rc == 0);
  Image r = read_png(dir + "/r.png");
  CHECK(r.width == 320);
  const int top = title_height(text_size_for(320), 2);
  const uint8_t* centre = r.at(160, top + 160);  // looking from +x at the most salient side: red
  CHECK(colormap_position(centre) > 0.8);
  REQUIRE((cr = run_cli_merged("render " + dir + "/s.ply --grey --compare " + dir + "/s.ply " + dir + "/s.ply --size 64 -o " +
                  dir + "/c.png")).rc == 0);
  {
    // --grey: the original drawn in grey (shaded, not white), no colour; the two "simplified"
    // panels (the same mesh) coloured by their distance to it, 0: the scale's low end.
    const Image c = read_png(dir + "/c.png");
    CHECK(c.width == 3 * 64 + 8);
    for (int panel = 0; panel < 3; ++panel) {
      const PixelCounts p = pixel_counts(c, panel * 68, 0, panel * 68 + 64, c.height);
      const int low = colour_in_range(c, panel * 68, 0, panel * 68 + 64, c.height, 0.0, 0.1);
      INFO("panel " << panel << ": coloured " << p.coloured << ", low end " << low << ", not white " << p.not_white);
      CHECK(p.not_white > 64 * 64 / 2);
      if (panel == 0)
        CHECK(p.coloured == 0);
      else
        CHECK(low > 64 * 64 / 3);
    }
  }

  // Curvature baseline: |H| is nearly uniform on a sphere, so any view sees about half of it.
  REQUIRE((cr = run_cli_merged("viewpoint " + dir + "/s.ply --score curvature --backend cpu --resolution 64 --restarts 2")).rc == 0);
  CHECK(cr.out.find("\"score\": \"curvature\"") != std::string::npos);
  CHECK(json_number(cr.out, "visible_fraction") > 0.4);
  CHECK(json_number(cr.out, "visible_fraction") < 0.6);
  CHECK(cr.out.find("\"exhaustive\": null") != std::string::npos);

  // Errors are one line: a bad choice is a usage error (exit 2), a bad file exit 1.
  CHECK((cr = run_cli_merged("viewpoint " + dir + "/s.ply --score nonsense")).rc == 2);
  CHECK(cr.out.find("error: --score: nonsense not in {saliency,curvature}") != std::string::npos);
  write_ply(dir + "/noq.ply", s, {});
  CHECK((cr = run_cli_merged("viewpoint " + dir + "/s.ply --saliency-from " + dir + "/noq.ply")).rc == 1);
  CHECK(cr.out.find("has no per-vertex `quality` property") != std::string::npos);
  // Numbers out of range are usage errors: exit code 2, the option and its range named.
  CHECK((cr = run_cli_merged("viewpoint " + dir + "/s.ply --resolution 2 --backend cpu")).rc == 2);
  CHECK(cr.out.find("error: --resolution: must be a whole number in [16, 8192], got '2'") != std::string::npos);
  CHECK((cr = run_cli_merged("render " + dir + "/s.ply --phi 100 -o " + dir + "/x.png")).rc == 2);
  CHECK(cr.out.find("error: --phi: must be a finite number in [-90, 90], got '100'") != std::string::npos);
}

TEST_CASE("cli: render and viewpoint --help name every input format, STL included", "[view][cli]") {
  for (const char* cmd : {"render", "viewpoint"}) {
    CliRun cr;
    REQUIRE((cr = run_cli_merged(std::string(cmd) + " --help")).rc == 0);
    INFO(cr.out);
    CHECK(cr.out.find("mesh (OBJ, PLY, OFF, STL, glTF, GLB, optionally .gz)") != std::string::npos);
    CHECK(cr.out.find("--json") != std::string::npos);
  }
}
