// meshsal: a perceptual colour map for per-vertex values (low = blue, high = red).
#pragma once
#include <cstdint>
#include <vector>

namespace meshsal {

// Turbo-like map of t in [0,1] to 8-bit RGB.
void colormap_rgb(double t, uint8_t rgb[3]);

// RGB per vertex (3 bytes each) of values scaled by their min..max over `mask` (all if empty).
std::vector<uint8_t> colormap_values(const std::vector<double>& values,
                                     const std::vector<uint8_t>& mask = {});

}  // namespace meshsal
