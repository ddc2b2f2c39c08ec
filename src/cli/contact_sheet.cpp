// meshsal batch: contact_sheet (see contact_sheet.h). The pictures are read back with
// stb_image (PNG only), so that models skipped by a resumed run are on the sheet too.
#include "contact_sheet.h"

#include <algorithm>
#include <cmath>
#include <memory>

#include "io/png_image.h"
#include "view/text.h"

#define STB_IMAGE_IMPLEMENTATION
#define STBI_ONLY_PNG
#define STBI_NO_STDIO_WARNINGS
#include <stb/stb_image.h>

namespace meshsal_cli {
namespace {

using meshsal::Image;

Image read_png(const std::string& path) {
  int w = 0, h = 0, comp = 0;
  std::unique_ptr<unsigned char, void (*)(void*)> pixels(stbi_load(path.c_str(), &w, &h, &comp, 3),
                                                         stbi_image_free);
  if (!pixels || w <= 0 || h <= 0) throw meshsal::Error(path + ": cannot read the picture");
  Image img(w, h);
  std::copy(pixels.get(), pixels.get() + size_t(w) * size_t(h) * 3, img.rgb.begin());
  return img;
}

// Shrinks `src` to fit side x side (aspect kept) by averaging the source pixels each
// target pixel covers.
Image shrink(const Image& src, int side) {
  const double scale = std::min({1.0, double(side) / src.width, double(side) / src.height});
  const int w = std::max(1, int(std::lround(src.width * scale)));
  const int h = std::max(1, int(std::lround(src.height * scale)));
  Image out(w, h);
  for (int y = 0; y < h; ++y) {
    const int y0 = y * src.height / h, y1 = std::max(y0 + 1, (y + 1) * src.height / h);
    for (int x = 0; x < w; ++x) {
      const int x0 = x * src.width / w, x1 = std::max(x0 + 1, (x + 1) * src.width / w);
      double sum[3] = {0, 0, 0};
      for (int sy = y0; sy < y1; ++sy)
        for (int sx = x0; sx < x1; ++sx)
          for (int c = 0; c < 3; ++c) sum[c] += src.at(sx, sy)[c];
      const double n = double(y1 - y0) * double(x1 - x0);
      for (int c = 0; c < 3; ++c) out.at(x, y)[c] = uint8_t(std::lround(sum[c] / n));
    }
  }
  return out;
}

std::string fitted_label(const std::string& name, double px, int width) {
  if (meshsal::text_width(name, px) <= width) return name;
  std::string s = name;
  while (!s.empty() && meshsal::text_width(s + "...", px) > width) s.pop_back();
  return s + "...";
}

}  // namespace

meshsal::Image contact_sheet(const std::vector<SheetItem>& items) {
  if (items.empty()) throw meshsal::Error("contact sheet: no best-view picture to show");
  const int n = int(items.size());
  const int cols = int(std::ceil(std::sqrt(double(n))));
  const int rows = (n + cols - 1) / cols;
  const int cell_w = kSheetThumb, cell_h = kSheetThumb + kSheetLabel;
  Image sheet(kSheetGap + cols * (cell_w + kSheetGap), kSheetGap + rows * (cell_h + kSheetGap));
  const uint8_t ink[3] = {20, 20, 20};
  const double px = 16;
  for (int i = 0; i < n; ++i) {
    const int x0 = kSheetGap + (i % cols) * (cell_w + kSheetGap);
    const int y0 = kSheetGap + (i / cols) * (cell_h + kSheetGap);
    const Image thumb = shrink(read_png(items[i].png), kSheetThumb);
    meshsal::blit(sheet, thumb, x0 + (cell_w - thumb.width) / 2, y0 + (kSheetThumb - thumb.height) / 2);
    const std::string label = fitted_label(items[i].name, px, cell_w - 4);
    meshsal::draw_text(sheet, x0 + (cell_w - meshsal::text_width(label, px)) / 2,
                       y0 + kSheetThumb + (kSheetLabel - int(px * 1.25)) / 2, label, px, ink);
  }
  return sheet;
}

}  // namespace meshsal_cli
