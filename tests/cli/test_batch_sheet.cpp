// `meshsal batch --contact-sheet`: one tile per model with its name, by pixels.
#include <catch2/catch.hpp>

#include <algorithm>

#include "png_check.h"
#include "test_batch_util.h"

using namespace meshsal_test;

namespace {

// The rows [first, last] of the band that hold dark (text) pixels: the label's height.
int ink_height(const meshsal::Image& img, int x0, int y0, int x1, int y1) {
  int first = -1, last = -1;
  for (int y = y0; y < y1; ++y)
    if (pixel_counts(img, x0, y, x1, y + 1).dark > 0) {
      if (first < 0) first = y;
      last = y;
    }
  return first < 0 ? 0 : last - first + 1;
}

int exact(const meshsal::Image& img, int x0, int y0, int x1, int y1, const uint8_t rgb[3]) {
  int n = 0;
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x) n += std::equal(rgb, rgb + 3, img.at(x, y));
  return n;
}

}  // namespace

TEST_CASE("batch: the contact sheet has a tile per model, a failed one marked, with names readable at 100%",
          "[batch]") {
  const fs::path dir = batch_scratch("sheet");
  const fs::path in = make_batch_inputs(dir), out = dir / "out", sheet = dir / "sheet.png";
  const std::string args = "batch " + in.string() + " -o " + out.string() + " --backend cpu --contact-sheet " +
                           sheet.string() + " --size 128 --resolution 32 --restarts 1";
  BatchRun r = run_meshsal(args, dir);
  INFO(r.err);
  CHECK(r.exit_code == 1);  // broken.obj
  for (const char* name : {"ball", "bumpy", "cube"}) CHECK(fs::exists(out / (std::string(name) + "_view.png")));
  // 4 tiles, broken.obj's too: 2 columns, 2 rows of 256 x (256 + 34) cells, 8 px apart and around.
  const int cw = 256 + 8, ch = 256 + 34 + 8;
  meshsal::Image img = read_png(sheet.string());
  CHECK(img.width == 8 + 2 * cw);
  CHECK(img.height == 8 + 2 * ch);
  const uint8_t grey[3] = {232, 232, 232}, red[3] = {210, 40, 40};
  for (int cell = 0; cell < 4; ++cell) {
    INFO("cell " << cell);
    const int x0 = 8 + (cell % 2) * cw, y0 = 8 + (cell / 2) * ch;
    const PixelCounts thumb = pixel_counts(img, x0, y0, x0 + 256, y0 + 256);
    const PixelCounts label = pixel_counts(img, x0, y0 + 256, x0 + 256, y0 + 290);
    CHECK(label.dark > 60);  // its name
    // Readable at 100%: capitals and ascenders at least 12 px tall (they were 5).
    CHECK(ink_height(img, x0, y0 + 256, x0 + 256, y0 + 290) >= 12);
    if (cell == 1) {  // broken.obj (input order: ball, broken, bumpy, cube)
      CHECK(exact(img, x0, y0, x0 + 256, y0 + 256, grey) > 30000);  // a grey tile
      CHECK(exact(img, x0, y0, x0 + 256, y0 + 256, red) > 800);     // with a red cross
      CHECK(thumb.dark > 200);                                       // "failed" and the error
      CHECK(thumb.coloured < 3000);                                   // no saliency colours
    } else {
      CHECK(thumb.coloured > 500);  // a mesh in saliency colours
      CHECK(exact(img, x0, y0, x0 + 256, y0 + 256, red) < 50);
    }
  }
  // A resumed run skips every good model and still puts all four on the sheet.
  fs::remove(sheet);
  r = run_meshsal(args, dir);
  CHECK(r.out.find("0 computed, 3 skipped, 1 failed") != std::string::npos);
  img = read_png(sheet.string());
  CHECK(img.width == 8 + 2 * cw);
  CHECK(pixel_counts(img, 8 + cw, 8 + ch, 8 + cw + 256, 8 + ch + 256).coloured > 500);  // cube
  CHECK(exact(img, 8 + cw, 8, 8 + cw + 256, 8 + 256, red) > 800);
}
