// meshsal: an 8-bit RGB image and writing it as PNG (stb_image_write).
#pragma once
#include <cstdint>
#include <string>
#include <vector>

namespace meshsal {

struct Image {
  int width = 0, height = 0;
  std::vector<uint8_t> rgb;  // 3 bytes per pixel, rows top to bottom

  Image() = default;
  Image(int w, int h, uint8_t r = 255, uint8_t g = 255, uint8_t b = 255);
  uint8_t* at(int x, int y) { return &rgb[(size_t(y) * size_t(width) + size_t(x)) * 3]; }
  const uint8_t* at(int x, int y) const { return &rgb[(size_t(y) * size_t(width) + size_t(x)) * 3]; }
};

// Copies `src` into `dst` with its top-left corner at (x, y) (clipped).
void blit(Image& dst, const Image& src, int x, int y);

// Writes a PNG through write_file_atomically (atomic_write.h). Throws Error naming path.
void write_png(const std::string& path, const Image& image);

}  // namespace meshsal
