// meshsal: the one colour scale of pictures and PLY vertex colours (ColorRange in meshsal.h:
// low = blue, high = dark red, linear from lo to hi).
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "meshsal/meshsal.h"

namespace meshsal {

// Turbo restricted to [0.1, 0.95] of its course, so t = 0 is a clear blue rather than
// Turbo's near-black end; t is clamped to [0, 1] (NaN: 0).
void colormap_rgb(double t, uint8_t rgb[3]);

// The scale's ends resolved to values.
struct ColorLimits {
  double lo = 0, hi = 1;
};

// Resolves `range` over the finite values inside `mask` (all if empty): percentiles by the
// nearest rank of the sorted values. hi <= lo (constant values) gives hi = lo + 1.
ColorLimits colour_limits(const std::vector<double>& values, const std::vector<uint8_t>& mask,
                          const ColorRange& range = {});

// Where v lies on the scale: sqrt of its linear position (v - lo) / (hi - lo), clamped to
// [0, 1]. The square root spreads the many low-to-moderate values (a face's eyes and mouth)
// over more colours while keeping the order and the top: the largest values stay the only
// dark red ones. The colour bar places its ticks with the same function.
double colour_position(double v, const ColorLimits& limits);

// RGB per value (3 bytes each) on the scale `limits`; values outside `mask` get the colour of lo.
std::vector<uint8_t> colormap_values(const std::vector<double>& values, const std::vector<uint8_t>& mask,
                                     const ColorLimits& limits);

// colour_limits then colormap_values: the PLY's colours and the pictures' share this.
std::vector<uint8_t> colormap_values(const std::vector<double>& values,
                                     const std::vector<uint8_t>& mask = {},
                                     const ColorRange& range = {});

}  // namespace meshsal
