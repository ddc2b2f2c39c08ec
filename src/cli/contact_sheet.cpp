// meshsal batch: contact_sheet (see contact_sheet.h). The pictures are read back with
// stb_image (PNG only), so that models skipped by a resumed run are on the sheet too.
#include "contact_sheet.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <memory>

#include "io/png_image.h"
#include "view/text.h"

#define STB_IMAGE_IMPLEMENTATION
#define STBI_ONLY_PNG
#define STBI_NO_STDIO_WARNINGS
#include <stb/stb_image.h>

namespace meshsal::cli {
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

std::string fitted_label(const std::string& name, double px, int width) { return meshsal::fit_text(name, px, width); }

// `text` broken into lines of at most `width` pixels at `px`, at spaces (a word wider than
// a line at any character), at most `max_lines`: the last one shortened with "..." when
// text is left over.
std::vector<std::string> wrapped(const std::string& text, double px, int width, size_t max_lines) {
  std::vector<std::string> lines;
  std::string line;
  size_t i = 0;
  bool more = false;
  while (i < text.size()) {
    size_t end = text.find(' ', i);
    if (end == std::string::npos) end = text.size();
    const std::string word = text.substr(i, end - i);
    i = end + 1;
    if (word.empty()) continue;
    const std::string joined = line.empty() ? word : line + " " + word;
    if (meshsal::text_width(joined, px) <= width) {
      line = joined;
      continue;
    }
    if (!line.empty()) {  // the word starts the next line
      lines.push_back(line);
      line.clear();
      if (lines.size() == max_lines) {
        more = true;
        break;
      }
    }
    // A word alone wider than a line: as many characters as fit, the rest on the next.
    std::string rest = word;
    while (meshsal::text_width(rest, px) > width) {
      size_t cut = rest.size();
      do {
        --cut;
        while (cut > 0 && (static_cast<unsigned char>(rest[cut]) & 0xc0) == 0x80) --cut;
      } while (cut > 1 && meshsal::text_width(rest.substr(0, cut), px) > width);
      if (cut == 0) cut = 1;  // not UTF-8: a byte at a time
      lines.push_back(rest.substr(0, cut));
      rest = rest.substr(cut);
      if (lines.size() == max_lines) {
        more = true;
        break;
      }
    }
    if (more) break;
    line = rest;
  }
  if (!more && !line.empty()) {
    if (lines.size() == max_lines) more = true;
    else lines.push_back(line);
  }
  if (more && !lines.empty()) {
    std::string& last = lines.back();
    while (!last.empty() && meshsal::text_width(last + "...", px) > width) {
      last.pop_back();
      while (!last.empty() && (static_cast<unsigned char>(last.back()) & 0xc0) == 0x80) last.pop_back();
    }
    last += "...";
  }
  return lines;
}

// A grey square with a red cross (failed) or without (skipped), the status in large letters
// and the message under it.
void draw_marked_tile(meshsal::Image& sheet, int x0, int y0, const SheetItem& item) {
  for (int y = y0; y < y0 + kSheetThumb; ++y)
    for (int x = x0; x < x0 + kSheetThumb; ++x)
      for (int c = 0; c < 3; ++c) sheet.at(x, y)[c] = kSheetTileGrey[c];
  const bool failed = item.status != "skipped";
  if (failed) {  // two strokes 9 px wide, 96 px long, centred 76 px from the top
    const int cx = x0 + kSheetThumb / 2, cy = y0 + 76, half = 48;
    for (int y = cy - half; y <= cy + half; ++y)
      for (int x = cx - half; x <= cx + half; ++x) {
        const int dx = x - cx, dy = y - cy;
        if (std::abs(dx - dy) <= 4 || std::abs(dx + dy) <= 4)
          for (int c = 0; c < 3; ++c) sheet.at(x, y)[c] = kSheetCrossRed[c];
      }
  }
  const uint8_t red[3] = {170, 20, 20}, grey[3] = {60, 60, 60};
  const std::string word = failed ? "failed" : "skipped";
  const double big = 26, small = 15;
  meshsal::draw_text(sheet, x0 + (kSheetThumb - meshsal::text_width(word, big)) / 2, y0 + 134, word, big,
                     failed ? red : grey);
  int y = y0 + 170;
  for (const std::string& line : wrapped(item.message, small, kSheetThumb - 16, 5)) {
    meshsal::draw_text(sheet, x0 + (kSheetThumb - meshsal::text_width(line, small)) / 2, y, line, small, grey);
    y += 17;
  }
}

}  // namespace

meshsal::Image contact_sheet(const std::vector<SheetItem>& items) {
  if (items.empty()) throw meshsal::Error("contact sheet: no model to show");
  const int n = int(items.size());
  const int cols = int(std::ceil(std::sqrt(double(n))));
  const int rows = (n + cols - 1) / cols;
  const int cell_w = kSheetThumb, cell_h = kSheetThumb + kSheetLabel;
  Image sheet(kSheetGap + cols * (cell_w + kSheetGap), kSheetGap + rows * (cell_h + kSheetGap));
  const uint8_t ink[3] = {20, 20, 20};
  const double px = kSheetLabelPx;
  for (int i = 0; i < n; ++i) {
    const int x0 = kSheetGap + (i % cols) * (cell_w + kSheetGap);
    const int y0 = kSheetGap + (i / cols) * (cell_h + kSheetGap);
    if (items[i].png.empty()) {
      draw_marked_tile(sheet, x0, y0, items[i]);
    } else {
      const Image thumb = shrink(read_png(items[i].png), kSheetThumb);
      meshsal::blit(sheet, thumb, x0 + (cell_w - thumb.width) / 2, y0 + (kSheetThumb - thumb.height) / 2);
    }
    const std::string label = fitted_label(items[i].name, px, cell_w - 4);
    meshsal::draw_text(sheet, x0 + (cell_w - meshsal::text_width(label, px)) / 2,
                       y0 + kSheetThumb + (kSheetLabel - int(px)) / 2, label, px, ink);
  }
  return sheet;
}

}  // namespace meshsal::cli
