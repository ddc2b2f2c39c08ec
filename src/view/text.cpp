#include "view/text.h"

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <map>
#include <memory>
#include <mutex>
#include <vector>

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wsign-compare"
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#define STB_TRUETYPE_IMPLEMENTATION
#define STBTT_STATIC
#include <stb/stb_truetype.h>
#pragma GCC diagnostic pop

namespace meshsal {
namespace {

struct Font {
  std::vector<unsigned char> bytes;
  stbtt_fontinfo info;
};

// Fonts stay loaded for the process (one per path; a picture draws a few dozen strings).
const Font& load_font() {
  static std::mutex mutex;
  static std::map<std::string, std::unique_ptr<Font>> fonts;
  const std::string path = font_path();
  std::lock_guard<std::mutex> lock(mutex);
  auto& slot = fonts[path];
  if (!slot) {
    std::ifstream in(path, std::ios::binary);
    auto f = std::make_unique<Font>();
    if (in) f->bytes.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    if (f->bytes.empty() || !stbtt_InitFont(&f->info, f->bytes.data(), stbtt_GetFontOffsetForIndex(f->bytes.data(), 0))) {
      fonts.erase(path);
      throw Error(path + ": no usable TrueType font for the pictures' text (install fonts-dejavu-core, or set MESHSAL_FONT)");
    }
    slot = std::move(f);
  }
  return *slot;
}

// UTF-8 to code points (a bad byte becomes '?').
std::vector<int> code_points(const std::string& s) {
  std::vector<int> out;
  for (size_t i = 0; i < s.size();) {
    unsigned char c = static_cast<unsigned char>(s[i]);
    int n = c < 0x80 ? 0 : (c >> 5) == 6 ? 1 : (c >> 4) == 14 ? 2 : (c >> 3) == 30 ? 3 : -1;
    if (n < 0 || i + size_t(n) >= s.size() + (n == 0 ? 1 : 0)) {
      out.push_back('?');
      ++i;
      continue;
    }
    int cp = n == 0 ? c : c & (0x3f >> n);
    for (int k = 1; k <= n; ++k) cp = (cp << 6) | (static_cast<unsigned char>(s[i + size_t(k)]) & 0x3f);
    out.push_back(cp);
    i += size_t(n) + 1;
  }
  return out;
}

}  // namespace

std::string font_path() {
  const char* env = std::getenv("MESHSAL_FONT");
  if (env && *env) return env;
  return "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf";
}

std::string fit_text(const std::string& text, double px, int width) {
  if (text_width(text, px) <= width) return text;
  std::string s = text;
  while (!s.empty() && text_width(s + "...", px) > width) {
    s.pop_back();
    while (!s.empty() && (static_cast<unsigned char>(s.back()) & 0xc0) == 0x80) s.pop_back();  // whole characters
  }
  return s + "...";
}

int text_width(const std::string& text, double px) {
  const Font& f = load_font();
  const float scale = stbtt_ScaleForPixelHeight(&f.info, float(px));
  std::vector<int> cps = code_points(text);
  double w = 0;
  for (size_t i = 0; i < cps.size(); ++i) {
    int adv = 0, lsb = 0;
    stbtt_GetCodepointHMetrics(&f.info, cps[i], &adv, &lsb);
    w += adv * scale;
    if (i + 1 < cps.size()) w += scale * stbtt_GetCodepointKernAdvance(&f.info, cps[i], cps[i + 1]);
  }
  return int(std::ceil(w));
}

void draw_text(Image& img, int x, int y, const std::string& text, double px, const uint8_t rgb[3]) {
  const Font& f = load_font();
  const float scale = stbtt_ScaleForPixelHeight(&f.info, float(px));
  int ascent = 0, descent = 0, gap = 0;
  stbtt_GetFontVMetrics(&f.info, &ascent, &descent, &gap);
  const int baseline = y + int(std::lround(ascent * scale));
  std::vector<int> cps = code_points(text);
  double pen = x;
  for (size_t i = 0; i < cps.size(); ++i) {
    int adv = 0, lsb = 0;
    stbtt_GetCodepointHMetrics(&f.info, cps[i], &adv, &lsb);
    const float shift = float(pen - std::floor(pen));
    int x0, y0, x1, y1;
    stbtt_GetCodepointBitmapBoxSubpixel(&f.info, cps[i], scale, scale, shift, 0, &x0, &y0, &x1, &y1);
    const int w = x1 - x0, h = y1 - y0;
    if (w > 0 && h > 0) {
      std::vector<unsigned char> cov(size_t(w) * size_t(h));
      stbtt_MakeCodepointBitmapSubpixel(&f.info, cov.data(), w, h, w, scale, scale, shift, 0, cps[i]);
      const int ox = int(std::floor(pen)) + x0, oy = baseline + y0;
      for (int r = 0; r < h; ++r)
        for (int c = 0; c < w; ++c) {
          const int X = ox + c, Y = oy + r;
          if (X < 0 || Y < 0 || X >= img.width || Y >= img.height) continue;
          const int a = cov[size_t(r) * size_t(w) + size_t(c)];
          uint8_t* p = img.at(X, Y);
          for (int k = 0; k < 3; ++k) p[k] = uint8_t((p[k] * (255 - a) + rgb[k] * a + 127) / 255);
        }
    }
    pen += adv * scale;
    if (i + 1 < cps.size()) pen += scale * stbtt_GetCodepointKernAdvance(&f.info, cps[i], cps[i + 1]);
  }
}

}  // namespace meshsal
