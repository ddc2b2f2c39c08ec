// Issue 39: the `meshsal view` page's controls, driven in headless Chromium through the
// page's test hook (page.html#test=STEP;..., web/viewer.js): the colour range and the
// wireframe change the pixels, "best view" after an orbit gives back the first frame's
// pixels exactly, the hover readout shows S, the first view's numbers are those `meshsal
// viewpoint` reports; and a batch gallery holds the viewer once, its pages only their data.
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>

#include <catch2/catch.hpp>

#include "cli/synthetic.h"
#include "chromium.h"
#include "cli_run.h"
#include "gltf_util.h"
#include "meshsal/meshsal.h"
#include "png_check.h"

using namespace meshsal;
using meshsal_test::chromium;
using meshsal_test::quoted;
using meshsal_test::text_of;
using meshsal_test::run_cli;
using meshsal_test::scratch_dir;

namespace {

Image shot(const std::filesystem::path& dir, const std::string& page, const std::string& hook, const std::string& name) {
  const std::string png = (dir / (name + ".png")).string();
  REQUIRE(chromium("--screenshot=" + png, "file://" + page + hook, (dir / (name + ".txt")).string()) == 0);
  Image img = meshsal_test::read_png(png);
  REQUIRE(img.width == 900);
  return img;
}

// Pixels that differ between two pictures of the view (left of the 300-pixel panel).
size_t differing(const Image& a, const Image& b) {
  size_t n = 0;
  for (int y = 0; y < 600; ++y)
    for (int x = 0; x < 600; ++x) {
      const uint8_t *p = a.at(x, y), *q = b.at(x, y);
      n += p[0] != q[0] || p[1] != q[1] || p[2] != q[2];
    }
  return n;
}

// The text of the element with this id in a dumped DOM ("" when absent).
std::string element_text(const std::string& dom, const std::string& id) {
  const size_t at = dom.find("id=\"" + id + "\"");
  if (at == std::string::npos) return "";
  const size_t open = dom.find('>', at), close = dom.find('<', open);
  return dom.substr(open + 1, close - open - 1);
}

// A number after "key": in a JSON text.
double json_number(const std::string& json, const std::string& key) {
  const size_t at = json.find("\"" + key + "\":");
  REQUIRE(at != std::string::npos);
  return std::stod(json.substr(at + key.size() + 3));
}

std::string base64_decoded(const std::string& in) {
  static const std::string t = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  uint32_t bits = 0;
  int n = 0;
  for (char c : in) {
    const size_t at = t.find(c);
    if (at == std::string::npos) continue;  // '=' padding
    bits = bits << 6 | uint32_t(at);
    if ((n += 6) >= 8) out += char((bits >> (n -= 8)) & 0xff);
  }
  return out;
}

}  // namespace

TEST_CASE("view page: range and wireframe change the pixels and best view gives the first frame back and hover shows S",
          "[cli][view][browser]") {
  REQUIRE(std::system("command -v chromium > /dev/null") == 0);  // tools/setup.sh installs it
  const auto dir = scratch_dir("view_page_controls");
  const std::string in = (dir / "m.obj").string(), page = (dir / "m.html").string();
  write_obj(in, make_bumpy_sphere(4));
  auto r = run_cli("view " + quoted(in) + " -o " + quoted(page) + " --backend cpu", dir);
  INFO(r.err);
  REQUIRE(r.rc == 0);

  // The page's model: a valid glTF (quantised, meshopt-compressed) by the Khronos validator.
  const std::string html = text_of(page);
  const size_t at = html.find("{\"glb\":\""), end = html.find('"', at + 8);
  REQUIRE(at != std::string::npos);
  const std::string glb = (dir / "page.glb").string();
  std::ofstream(glb, std::ios::binary) << base64_decoded(html.substr(at + 8, end - at - 8));
  std::string report;
  const int valid = meshsal_test::validate_gltf(glb, &report);
  INFO(report);
  CHECK(valid == 0);
  CHECK(report.find(" 0 errors, 0 warnings") != std::string::npos);

  const Image first = shot(dir, page, "", "first");
  // The model with a margin: the view's border rows and columns are background (x = 599 is
  // the panel's border).
  for (int i = 0; i < 598; i += 7)
    for (const auto& [x, y] : {std::pair{i, 0}, std::pair{i, 599}, std::pair{0, i}, std::pair{597, i}}) {
      const uint8_t* p = first.at(x, y);
      CHECK(int(p[0]) + p[1] + p[2] > 3 * 240);
    }
  const Image range = shot(dir, page, "#test=range:30,70", "range");
  CHECK(differing(first, range) > 5000);  // other colours over much of the model
  const Image wire = shot(dir, page, "#test=wireframe", "wire");
  CHECK(differing(first, wire) > 1000);  // edges drawn
  const Image orbit = shot(dir, page, "#test=orbit", "orbit");
  CHECK(differing(first, orbit) > 5000);
  const Image back = shot(dir, page, "#test=orbit;best", "back");
  CHECK(differing(first, back) == 0);  // exactly the first frame

  // The DOM after a hover at the view's centre: S and its percentile, no error, and the
  // first view's numbers as `meshsal viewpoint` gives them.
  const std::string dom_file = (dir / "dom.html").string();
  REQUIRE(chromium("--dump-dom", "file://" + page + "#test=orbit;hover:0.5,0.5", dom_file) == 0);
  const std::string dom = text_of(dom_file);
  INFO(dom.substr(0, 600));
  CHECK(dom.find("data-status=\"drawn\"") != std::string::npos);
  CHECK(dom.find("data-test=\"done\"") != std::string::npos);
  const std::string readout = element_text(dom, "readout");
  INFO(readout);
  CHECK(readout.find("S under the cursor: ") == 0);
  CHECK(readout.find("percentile") != std::string::npos);
  const size_t v = dom.find("data-value=\"");
  REQUIRE(v != std::string::npos);
  const double s = std::stod(dom.substr(v + 12));
  CHECK(std::isfinite(s));
  CHECK(s >= 0);
  CHECK(element_text(dom, "azimuth") != element_text(dom, "best-azimuth"));  // the orbit turned it

  r = run_cli("viewpoint " + quoted(in) + " --backend cpu", dir);
  REQUIRE(r.rc == 0);
  const std::string& j = r.out;
  CHECK(std::abs(std::stod(element_text(dom, "best-azimuth")) - json_number(j, "theta_deg")) <= 0.051);
  CHECK(std::abs(std::stod(element_text(dom, "best-elevation")) - json_number(j, "phi_deg")) <= 0.051);
  const double U = json_number(j, "visible_score");
  CHECK(std::abs(std::stod(element_text(dom, "best-u")) - U) <= 1e-3 * U);
  CHECK(std::abs(std::stod(element_text(dom, "best-fraction")) - 100 * json_number(j, "visible_fraction")) <= 0.051);
}

TEST_CASE("batch --html: the gallery holds the viewer once beside index.html and the pages load it",
          "[cli][view][batch][browser]") {
  const auto dir = scratch_dir("view_gallery_size");
  std::filesystem::create_directories(dir / "in");
  const int n = 3;
  for (int i = 0; i < n; ++i) write_obj((dir / "in" / ("m" + std::to_string(i) + ".obj")).string(), make_sphere(1.0, 2 + i % 2));
  const std::string out = (dir / "out").string();
  auto r = run_cli("batch " + quoted((dir / "in").string()) + " -o " + quoted(out) + " --html --backend cpu", dir);
  INFO(r.out + r.err);
  REQUIRE(r.rc == 0);
  CHECK(r.out.find("wrote  " + out + "/meshsal-viewer.js") != std::string::npos);
  const std::string viewer = text_of(dir / "out" / "meshsal-viewer.js");
  CHECK(viewer.find("Copyright 2010-2026 Three.js Authors") != std::string::npos);
  CHECK(viewer.size() > 200000);
  size_t pages = 0, data = 0;
  for (int i = 0; i < n; ++i) {
    const std::string page = text_of(dir / "out" / ("m" + std::to_string(i) + "_view.html"));
    CHECK(page.find("<script src=\"meshsal-viewer.js\"") != std::string::npos);
    CHECK(page.find("Three.js Authors") == std::string::npos);  // not the bundle
    const size_t at = page.find("{\"glb\":\""), end = page.find('"', at + 8);
    REQUIRE(at != std::string::npos);
    pages += page.size(), data += end - at;
  }
  // The gallery grows by the models' data (and a page's few kilobytes of markup), not by a
  // viewer per model.
  CHECK(pages - data < size_t(n) * 30000);
  CHECK(pages < viewer.size());

  // A page of the gallery draws with the shared viewer.
  const std::string dom_file = (dir / "dom.html").string();
  REQUIRE(chromium("--dump-dom", "file://" + out + "/m0_view.html", dom_file) == 0);
  const std::string dom = text_of(dom_file);
  INFO(dom.substr(0, 400));
  CHECK(dom.find("data-status=\"drawn\"") != std::string::npos);

  // The viewer file is an output as the others: one that is an input (here the list of
  // models) is refused before any work, and left as it was.
  const auto dir2 = scratch_dir("view_gallery_clash");
  std::filesystem::create_directories(dir2 / "out");
  const std::string list = (dir2 / "out" / "meshsal-viewer.js").string();
  std::ofstream(list) << (dir / "in" / "m0.obj").string() << "\n";
  r = run_cli("batch @" + quoted(list) + " -o " + quoted((dir2 / "out").string()) + " --html --backend cpu", dir2);
  CHECK(r.rc != 0);
  CHECK(r.err.find("meshsal-viewer.js") != std::string::npos);
  CHECK(text_of(list) == (dir / "in" / "m0.obj").string() + "\n");
  CHECK(!std::filesystem::exists(dir2 / "out" / "m0_view.html"));
}
