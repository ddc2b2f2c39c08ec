// meshsal: helpers for the Image of meshsal.h; write_png (stb_image_write) is declared there.
#pragma once
#include "meshsal/meshsal.h"
#include <cstdint>
#include <string>
#include <vector>

namespace meshsal {

// Copies `src` into `dst` with its top-left corner at (x, y) (clipped).
void blit(Image& dst, const Image& src, int x, int y);

}  // namespace meshsal
