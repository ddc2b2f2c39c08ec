// `meshsal view`: the page opens in headless Chromium (SwiftShader's WebGL), draws its first
// frame with no error, and shows the model in the saliency colours; a mesh over --max-faces
// is shown as a simplified copy and the page says so. One browser test for the suite.
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>

#include <catch2/catch.hpp>

#include "cli/synthetic.h"
#include "cli_run.h"
#include "meshsal/meshsal.h"
#include "png_check.h"

using namespace meshsal;
using meshsal_test::quoted;
using meshsal_test::run_cli;
using meshsal_test::scratch_dir;

namespace {

std::string text_of(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// Headless Chromium on `page` (WebGL through SwiftShader); `what`: --dump-dom or
// --screenshot=FILE. Its output goes to `out`.
int chromium(const std::string& what, const std::string& page, const std::string& out) {
  const std::string cmd = "timeout 120 chromium --headless --no-sandbox --disable-gpu-sandbox --use-angle=swiftshader "
                          "--enable-unsafe-swiftshader --hide-scrollbars --window-size=900,600 "
                          "--virtual-time-budget=20000 " + what + " 'file://" + page + "' > '" + out + "' 2>/dev/null";
  return WEXITSTATUS(std::system(cmd.c_str()));
}

}  // namespace

TEST_CASE("view: the page draws the model in colour in headless Chromium, with no error", "[cli][view][browser]") {
  REQUIRE(std::system("command -v chromium > /dev/null") == 0);  // tools/setup.sh installs it
  const auto dir = scratch_dir("view_page");
  const std::string in = (dir / "m.obj").string(), page = (dir / "m.html").string();
  write_obj(in, make_bumpy_sphere(4));
  auto r = run_cli("view " + quoted(in) + " -o " + quoted(page) + " --backend cpu", dir);
  INFO(r.err);
  REQUIRE(r.rc == 0);
  const std::string html = text_of(page);
  CHECK(html.find("<title>meshsal: m.obj</title>") != std::string::npos);
  CHECK(html.find("Copyright 2010-2026 Three.js Authors") != std::string::npos);  // the bundle, its licence kept
  CHECK(html.find("src=\"http") == std::string::npos);  // nothing to fetch: it opens offline
  CHECK(html.find("<link") == std::string::npos);

  REQUIRE(chromium("--dump-dom", page, (dir / "dom.html").string()) == 0);
  const std::string dom = text_of(dir / "dom.html");
  INFO(dom.substr(0, 400));
  CHECK(dom.find("data-status=\"drawn\"") != std::string::npos);  // first frame drawn, no error logged
  CHECK(dom.find("data-status=\"error") == std::string::npos);

  const std::string shot = (dir / "shot.png").string();
  REQUIRE(chromium("--screenshot=" + shot, page, (dir / "chromium.txt").string()) == 0);
  const Image img = meshsal_test::read_png(shot);
  REQUIRE(img.width == 900);
  // The model fills the middle of the view (left of the 300-pixel panel) in the saliency
  // colours: saturated pixels (blue to red), not the white background or grey.
  size_t coloured = 0, total = 0;
  for (int y = 150; y < 450; ++y)
    for (int x = 150; x < 450; ++x, ++total) {
      const uint8_t* p = img.at(x, y);
      const int hi = std::max({p[0], p[1], p[2]}), lo = std::min({p[0], p[1], p[2]});
      coloured += hi - lo > 60;
    }
  CHECK(coloured > total / 2);
  // The corner of the view is background.
  const uint8_t* corner = img.at(5, 5);
  CHECK(int(corner[0]) + corner[1] + corner[2] > 3 * 240);
}

TEST_CASE("view: a mesh over --max-faces is shown as a simplified copy, and the page says so", "[cli][view]") {
  const auto dir = scratch_dir("view_big");
  const std::string in = (dir / "m.obj").string(), page = (dir / "m.html").string();
  write_obj(in, make_bumpy_sphere(4));  // 5120 faces
  auto r = run_cli("view " + quoted(in) + " -o " + quoted(page) + " --backend cpu --max-faces 1000 --json", dir);
  INFO(r.err);
  REQUIRE(r.rc == 0);
  CHECK(r.out.find("\"simplified_copy\": true") != std::string::npos);
  const std::string html = text_of(page);
  CHECK(html.find("The page shows a copy simplified to 1000 faces (plain quadrics, the saliency carried): the mesh "
                  "has 5120.") != std::string::npos);
  // Without the limit, the whole mesh and no note; the page is smaller with the copy.
  r = run_cli("view " + quoted(in) + " -o " + quoted((dir / "whole.html").string()) + " --backend cpu -q", dir);
  REQUIRE(r.rc == 0);
  const std::string whole = text_of(dir / "whole.html");
  CHECK(whole.find("simplified to") == std::string::npos);
  CHECK(whole.size() > html.size());
  // Outputs: .html only, never the input.
  r = run_cli("view " + quoted(in) + " -o " + quoted((dir / "m.png").string()), dir);
  CHECK(r.rc == 1);
  CHECK(r.err.find("-o must be a .html file") != std::string::npos);
}

TEST_CASE("view: batch --html writes each model's page and a gallery, failed models marked", "[cli][view][batch]") {
  const auto dir = scratch_dir("view_batch");
  std::filesystem::create_directories(dir / "in");
  write_obj((dir / "in" / "ball.obj").string(), make_bumpy_sphere(3));
  std::ofstream(dir / "in" / "broken.obj") << "v 0 0 0\nf 1 2 3\n";
  const std::string out = (dir / "out").string();
  const std::string args = "batch " + quoted((dir / "in").string()) + " -o " + quoted(out) + " --html --backend cpu";
  auto r = run_cli(args, dir);
  CHECK(r.rc == 1);  // one model failed
  CHECK(r.out.find("2 models: 1 computed, 0 skipped, 1 failed") != std::string::npos);
  // The model's page is the one `meshsal view` writes (its title, the bundle, the GLB).
  const std::string page = text_of(dir / "out" / "ball_view.html");
  CHECK(page.find("<title>meshsal: ball.obj</title>") != std::string::npos);
  CHECK(page.find("data-status=\"loading\"") != std::string::npos);
  CHECK(std::filesystem::exists(dir / "out" / "ball_view.png"));  // --html implies the picture
  const std::string gallery = text_of(dir / "out" / "index.html");
  CHECK(gallery.find("<a href=\"ball_view.html\"><img src=\"ball_view.png\"") != std::string::npos);
  CHECK(gallery.find("<div class=\"card failed\"><div class=\"name\">broken.obj: failed</div>") != std::string::npos);
  // Run again: the model is up to date, and the gallery still opens its page.
  r = run_cli(args, dir);
  CHECK(r.out.find("0 computed, 1 skipped, 1 failed") != std::string::npos);
  CHECK(text_of(dir / "out" / "index.html").find("<a href=\"ball_view.html\">") != std::string::npos);
}
