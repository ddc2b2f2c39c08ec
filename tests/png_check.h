// Reading the pictures the tool wrote back for pixel checks: a scratch folder, the PNG
// decoded to RGB, and a pixel's position on the colour scale. stb_image is implemented in
// stb_image_impl.cpp.
#pragma once
#include <stdlib.h>

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

}  // namespace meshsal_test
