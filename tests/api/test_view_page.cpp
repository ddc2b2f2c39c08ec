// `meshsal view`: the page opens in headless Chromium (SwiftShader's WebGL), draws its first
// frame with no error, and shows the model in the saliency colours; a mesh over --max-faces
// is shown as a simplified copy and the page says so. One browser test for the suite.
// Issue 36 (8): the template filled in one pass, names shown escaped, the faces reported
// the faces shown.
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>

#include <catch2/catch.hpp>

#include "api/page_template.h"
#include "cli/synthetic.h"
#include "core/html_text.h"
#include "core/utf8.h"
#include "chromium.h"
#include "cli_run.h"
#include "meshsal/meshsal.h"
#include "png_check.h"

using namespace meshsal;
using meshsal_test::chromium;
using meshsal_test::quoted;
using meshsal_test::text_of;
using meshsal_test::run_cli;
using meshsal_test::scratch_dir;

namespace {

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

  REQUIRE(chromium("--dump-dom", "file://" + page, (dir / "dom.html").string()) == 0);
  const std::string dom = text_of(dir / "dom.html");
  INFO(dom.substr(0, 400));
  CHECK(dom.find("data-status=\"drawn\"") != std::string::npos);  // first frame drawn, no error logged
  CHECK(dom.find("data-status=\"error") == std::string::npos);

  const std::string shot = (dir / "shot.png").string();
  REQUIRE(chromium("--screenshot=" + shot, "file://" + page, (dir / "chromium.txt").string()) == 0);
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

namespace {

std::string base64_decoded(const std::string& in) {
  std::string out;
  uint32_t bits = 0;
  int n = 0;
  for (char c : in) {
    const char* t = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    const char* at = c ? std::strchr(t, c) : nullptr;
    if (!at) continue;  // '=' padding
    bits = bits << 6 | uint32_t(at - t);
    if ((n += 6) >= 8) out += char((bits >> (n -= 8)) & 0xff);
  }
  return out;
}

// The faces of the mesh a page shows: its embedded GLB's index accessor (the page's GLB is
// quantised and meshopt-compressed, which meshsal's reader does not decode: its JSON says
// the count). The accessors are POSITION, _SALIENCY, then the indices.
size_t faces_shown(const std::string& html, const std::filesystem::path& dir) {
  (void)dir;
  const std::string key = "{\"glb\":\"";
  const size_t at = html.find(key);
  REQUIRE(at != std::string::npos);
  const size_t end = html.find('"', at + key.size());
  const std::string glb = base64_decoded(html.substr(at + key.size(), end - at - key.size()));
  REQUIRE(glb.size() > 20);
  REQUIRE(glb.compare(0, 4, "glTF") == 0);
  uint32_t json_bytes = 0;
  std::memcpy(&json_bytes, glb.data() + 12, 4);
  const std::string json = glb.substr(20, json_bytes);
  size_t k = json.find("\"accessors\":[");
  REQUIRE(k != std::string::npos);
  for (int i = 0; i < 3; ++i) {
    k = json.find("\"count\":", k + 1);
    REQUIRE(k != std::string::npos);
  }
  const size_t indices = std::stoul(json.substr(k + 8));
  CHECK(indices % 3 == 0);
  return indices / 3;
}

size_t count_of(const std::string& text, const std::string& what) {
  size_t n = 0;
  for (size_t at = 0; (at = text.find(what, at)) != std::string::npos; at += what.size()) ++n;
  return n;
}

}  // namespace

TEST_CASE("view: the faces --json reports are the faces the page shows, budget reached or not", "[cli][view]") {
  const auto dir = scratch_dir("view_max_faces");
  const std::string in = (dir / "m.obj").string(), page = (dir / "m.html").string();
  write_obj(in, make_bumpy_sphere(3));  // 1280 faces, closed: never fewer than 4
  auto r = run_cli("view " + quoted(in) + " -o " + quoted(page) + " --backend cpu --max-faces 1 --json", dir);
  INFO(r.err);
  REQUIRE(r.rc == 0);
  std::string html = text_of(page);
  const size_t shown = faces_shown(html, dir);
  CHECK(shown >= 4);
  CHECK(shown < 1280);
  CHECK(r.out.find("\"shown_faces\": " + std::to_string(shown) + ",") != std::string::npos);
  CHECK(r.out.find("\"max_faces\": 1,") != std::string::npos);
  CHECK(r.out.find("\"max_faces_reached\": false") != std::string::npos);
  CHECK(html.find("The page shows a copy simplified to " + std::to_string(shown) + " faces, as far as the simplifier "
                  "could go towards the 1 asked (plain quadrics, the saliency carried): the mesh has 1280.") !=
        std::string::npos);
  // A note says so too.
  r = run_cli("view " + quoted(in) + " -o " + quoted(page) + " --backend cpu --max-faces 1", dir);
  REQUIRE(r.rc == 0);
  CHECK(r.err.find("note: the page shows a copy simplified to " + std::to_string(shown) +
                   " faces, not the 1 of --max-faces: the simplifier could go no further (the mesh has 1280)\n") !=
        std::string::npos);
  // A budget it reaches: the count asked, shown and reported.
  r = run_cli("view " + quoted(in) + " -o " + quoted(page) + " --backend cpu --max-faces 300 --json", dir);
  REQUIRE(r.rc == 0);
  html = text_of(page);
  CHECK(faces_shown(html, dir) == 300);
  CHECK(r.out.find("\"shown_faces\": 300,") != std::string::npos);
  CHECK(r.out.find("\"max_faces_reached\": true") != std::string::npos);
  // The whole mesh: its own count.
  r = run_cli("view " + quoted(in) + " -o " + quoted(page) + " --backend cpu --json", dir);
  REQUIRE(r.rc == 0);
  CHECK(faces_shown(text_of(page), dir) == 1280);
  CHECK(r.out.find("\"simplified_copy\": false, \"shown_faces\": 1280,") != std::string::npos);
}

TEST_CASE("view: the template is filled in one pass: a name holding placeholders stays that text", "[cli][view]") {
  // The filler alone: a value is never searched again; a missing placeholder is an error.
  CHECK(fill_template("<h1>@A@</h1>@B@", {{"@A@", "@B@ and @A@"}, {"@B@", "b"}}) == "<h1>@B@ and @A@</h1>b");
  CHECK(fill_template("a@b @X@@", {{"@X@", "x"}}) == "a@b x@");
  CHECK_THROWS_WITH(fill_template("@A@", {{"@A@", "a"}, {"@B@", "b"}}), "the page template has no placeholder @B@");

  const auto dir = scratch_dir("view_placeholders");
  const std::string name = "@BUNDLE@ @DATA@ @TITLE@ @NOTE@ @STATS@.obj";
  const std::string in = (dir / name).string(), page = (dir / "m.html").string();
  write_obj(in, make_sphere(1.0, 2));
  const auto r = run_cli("view " + quoted(in) + " -o " + quoted(page) + " --backend cpu", dir);
  INFO(r.err);
  REQUIRE(r.rc == 0);
  const std::string html = text_of(page);
  CHECK(html.find("<title>meshsal: " + name + "</title>") != std::string::npos);
  CHECK(html.find("<h1>" + name + "</h1>") != std::string::npos);
  CHECK(count_of(html, "Copyright 2010-2026 Three.js Authors") == 1);  // the bundle once, in its <script>
  CHECK(count_of(html, "{\"glb\":\"") == 1);
  CHECK(count_of(html, "@BUNDLE@") == 2);  // the title and the heading, nothing else
  CHECK(count_of(html, "@DATA@") == 2);
  CHECK(html.find("<script id=\"meshsal-data\" type=\"application/json\">{\"glb\":\"") != std::string::npos);
  CHECK(faces_shown(html, dir) == 320);
}

TEST_CASE("view and batch --html: names not UTF-8 and bidi controls are shown escaped in pages and the gallery",
          "[cli][view][batch]") {
  // The rule (core/utf8.h): every bidirectional control shown as \uXXXX, other bytes as \xXX.
  for (unsigned code : {0x061cu, 0x200eu, 0x200fu, 0x202au, 0x202bu, 0x202cu, 0x202du, 0x202eu, 0x2066u, 0x2067u,
                        0x2068u, 0x2069u}) {
    std::string utf8;
    if (code < 0x800) utf8 = {char(0xc0 | (code >> 6)), char(0x80 | (code & 0x3f))};
    else utf8 = {char(0xe0 | (code >> 12)), char(0x80 | ((code >> 6) & 0x3f)), char(0x80 | (code & 0x3f))};
    char want[16];
    std::snprintf(want, sizeof want, "a\\u%04xb", code);
    CHECK(html_escaped("a" + utf8 + "b") == want);
  }
  CHECK(html_escaped("<caf\xe9 \"\xc3\xa9\">&\x1b") == "&lt;caf\\xe9 &quot;\xc3\xa9&quot;&gt;&amp;\\x1b");
  CHECK(html_escaped("\xe2\x80\x8b zero width space, \xd7\x90 alef") == "\xe2\x80\x8b zero width space, \xd7\x90 alef");

  const auto dir = scratch_dir("view_names");
  std::filesystem::create_directories(dir / "in");
  const std::string rlo = "\xe2\x80\xae", lri = "\xe2\x81\xa6";  // U+202E, U+2066
  const std::string evil = "evil" + rlo + "gnp.obj", latin1 = "caf\xe9.obj", broken = "bad" + lri + ".obj";
  write_obj((dir / "in" / evil).string(), make_sphere(1.0, 2));
  write_obj((dir / "in" / latin1).string(), make_sphere(1.0, 1));
  std::ofstream(dir / "in" / broken) << "v 0 0 0\nf 1 2 3\n";
  // view: the title, the heading, and the statistics' --saliency-from name.
  const std::string page = (dir / "p.html").string();
  auto r = run_cli("view " + quoted((dir / "in" / evil).string()) + " -o " + quoted(page) + " --backend cpu", dir);
  INFO(r.err);
  REQUIRE(r.rc == 0);
  std::string html = text_of(page);
  CHECK(html.find("<title>meshsal: evil\\u202egnp.obj</title>") != std::string::npos);
  CHECK(html.find("<h1>evil\\u202egnp.obj</h1>") != std::string::npos);
  CHECK(html.find(rlo) == std::string::npos);
  CHECK(meshsal::valid_utf8(html));
  const std::string s_ply = (dir / ("s" + rlo + "\xff.ply")).string();
  r = run_cli("saliency " + quoted((dir / "in" / latin1).string()) + " -o " + quoted(s_ply) + " --backend cpu -q", dir);
  REQUIRE(r.rc == 0);
  r = run_cli("view " + quoted((dir / "in" / latin1).string()) + " -o " + quoted(page) + " --saliency-from " +
                  quoted(s_ply) + " --backend cpu",
              dir);
  REQUIRE(r.rc == 0);
  html = text_of(page);
  CHECK(html.find("<title>meshsal: caf\\xe9.obj</title>") != std::string::npos);
  CHECK(html.find("<td>saliency</td><td>" + meshsal::visible_text(s_ply) + "</td>") != std::string::npos);
  CHECK(html.find("s\\u202e\\xff.ply</td>") != std::string::npos);
  CHECK(meshsal::valid_utf8(html));
  // batch --html: each page's title and the gallery's cards (a failed one's message too).
  r = run_cli("batch " + quoted((dir / "in").string()) + " -o " + quoted((dir / "out").string()) +
                  " --html --backend cpu -q",
              dir);
  CHECK(r.rc == 1);  // the broken one
  const std::string gallery = text_of(dir / "out" / "index.html");
  CHECK(meshsal::valid_utf8(gallery));
  CHECK(gallery.find(rlo) == std::string::npos);
  CHECK(gallery.find(lri) == std::string::npos);
  CHECK(gallery.find("alt=\"evil\\u202egnp.obj\"></a><div class=\"name\"><a href=\"evil%E2%80%AEgnp_view.html\">"
                     "evil\\u202egnp.obj</a>") != std::string::npos);
  CHECK(gallery.find("<a href=\"caf%E9_view.html\"><img src=\"caf%E9_view.png\" alt=\"caf\\xe9.obj\">") !=
        std::string::npos);
  CHECK(gallery.find("<div class=\"name\">bad\\u2066.obj: failed</div><div class=\"why\">") != std::string::npos);
  CHECK(gallery.find("bad\\u2066.obj: ") != std::string::npos);
  const std::string evil_page = text_of(dir / "out" / ("evil" + rlo + "gnp_view.html"));
  CHECK(evil_page.find("<title>meshsal: evil\\u202egnp.obj</title>") != std::string::npos);
  CHECK(meshsal::valid_utf8(evil_page));
  CHECK(meshsal::valid_utf8(text_of(dir / "out" / "caf\xe9_view.html")));
}
