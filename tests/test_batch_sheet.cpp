// `meshsal batch --contact-sheet`: one thumbnail per model with its name, by pixels.
#include <catch2/catch.hpp>

#include "png_check.h"
#include "test_batch_util.h"

using namespace meshsal_test;

namespace {

// Pixels in [x0, x1) x [y0, y1) that are saturated colour (the saliency colours), dark
// (text) and not white.
struct Counts {
  int coloured = 0, dark = 0, not_white = 0;
};
Counts count(const meshsal::Image& img, int x0, int y0, int x1, int y1) {
  Counts c;
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x) {
      const uint8_t* p = img.at(x, y);
      const int mx = std::max({p[0], p[1], p[2]}), mn = std::min({p[0], p[1], p[2]});
      c.coloured += mx - mn > 80;
      c.dark += mx < 100;
      c.not_white += mn < 255;
    }
  return c;
}

}  // namespace

TEST_CASE("batch: the contact sheet has one named thumbnail per good model", "[batch]") {
  const fs::path dir = batch_scratch("sheet");
  const fs::path in = make_batch_inputs(dir), out = dir / "out", sheet = dir / "sheet.png";
  const std::string args = "batch " + in.string() + " -o " + out.string() + " --backend cpu --contact-sheet " +
                           sheet.string() + " --size 128 --resolution 32 --restarts 1";
  BatchRun r = run_meshsal(args, dir);
  INFO(r.err);
  CHECK(r.exit_code == 1);  // broken.obj
  for (const char* name : {"ball", "bumpy", "cube"}) CHECK(fs::exists(out / (std::string(name) + "_view.png")));
  // 3 thumbnails: 2 columns, 2 rows of 256 x (256 + 28) cells, 8 px apart and around.
  meshsal::Image img = read_png(sheet.string());
  CHECK(img.width == 8 + 2 * (256 + 8));
  CHECK(img.height == 8 + 2 * (256 + 28 + 8));
  for (int cell = 0; cell < 4; ++cell) {
    INFO("cell " << cell);
    const int x0 = 8 + (cell % 2) * 264, y0 = 8 + (cell / 2) * 292;
    const Counts thumb = count(img, x0, y0, x0 + 256, y0 + 256);
    const Counts label = count(img, x0, y0 + 256, x0 + 256, y0 + 284);
    if (cell < 3) {
      CHECK(thumb.coloured > 500);  // a mesh in saliency colours
      CHECK(label.dark > 20);       // its name
    } else {
      CHECK(thumb.not_white == 0);  // no fourth model
      CHECK(label.not_white == 0);
    }
  }
  // A resumed run skips every model and still puts all three on the sheet.
  fs::remove(sheet);
  r = run_meshsal(args, dir);
  CHECK(r.out.find("0 computed, 3 skipped, 1 failed") != std::string::npos);
  img = read_png(sheet.string());
  CHECK(img.width == 8 + 2 * (256 + 8));
  CHECK(count(img, 8 + 264, 8, 8 + 264 + 256, 8 + 256).coloured > 500);
}
