// Reading the pictures the tool wrote back for pixel checks: a scratch folder, the PNG
// decoded to RGB, and a pixel's position on the colour scale. stb_image is implemented in
// stb_image_impl.cpp.
#pragma once
#include <stdlib.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <string>

#include <catch2/catch.hpp>
#include <stb/stb_image.h>

#include "io/colormap.h"
#include "meshsal/meshsal.h"

namespace meshsal_test {

// A fresh folder under /tmp, removed with everything in it when the test ends.
struct PictureDir {
  std::string path;
  PictureDir() {
    char tmpl[] = "/tmp/meshsal_pictures_XXXXXX";
    const char* d = mkdtemp(tmpl);
    REQUIRE(d != nullptr);
    path = d;
  }
  ~PictureDir() {
    std::error_code ec;
    std::filesystem::remove_all(path, ec);
  }
};

inline meshsal::Image read_png(const std::string& path) {
  int w = 0, h = 0, c = 0;
  unsigned char* data = stbi_load(path.c_str(), &w, &h, &c, 3);
  REQUIRE(data != nullptr);
  meshsal::Image img;
  img.width = w;
  img.height = h;
  img.rgb.assign(data, data + size_t(w) * size_t(h) * 3);
  stbi_image_free(data);
  return img;
}

// Pixels in [x0, x1) x [y0, y1) that are saturated colour (the saliency colours: max - min
// channel > 80), dark (text, dark shading: every channel < 100) and not white.
struct PixelCounts {
  int coloured = 0, dark = 0, not_white = 0;
};
inline PixelCounts pixel_counts(const meshsal::Image& img, int x0, int y0, int x1, int y1) {
  PixelCounts c;
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
inline PixelCounts pixel_counts(const meshsal::Image& img) { return pixel_counts(img, 0, 0, img.width, img.height); }

// The colour-map position t of a (possibly shaded) colour: the t whose colour has the nearest
// chromaticity (shading scales r, g, b alike).
inline double colormap_position(const uint8_t* p) {
  double sum = double(p[0]) + p[1] + p[2] + 1e-9, best = 1e9, best_t = 0;
  for (int k = 0; k <= 200; ++k) {
    uint8_t c[3];
    meshsal::colormap_rgb(k / 200.0, c);
    double cs = double(c[0]) + c[1] + c[2] + 1e-9, e = 0;
    for (int j = 0; j < 3; ++j) e += std::pow(p[j] / sum - c[j] / cs, 2);
    if (e < best) {
      best = e;
      best_t = k / 200.0;
    }
  }
  return best_t;
}

// The saturated-colour pixels (as pixel_counts) in [x0, x1) x [y0, y1) whose colour-map
// position is in [lo, hi]: where the saliency scale's low or high end is drawn.
inline int colour_in_range(const meshsal::Image& img, int x0, int y0, int x1, int y1, double lo, double hi) {
  int n = 0;
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x) {
      const uint8_t* p = img.at(x, y);
      if (std::max({p[0], p[1], p[2]}) - std::min({p[0], p[1], p[2]}) <= 80) continue;
      const double t = colormap_position(p);
      n += t >= lo && t <= hi;
    }
  return n;
}

}  // namespace meshsal_test
