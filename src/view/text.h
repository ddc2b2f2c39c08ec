// meshsal: text on pictures, rasterised from a TrueType font by stb_truetype (anti-aliased
// coverage blended onto the image).
//
// The font: $MESHSAL_FONT when set, else DejaVu Sans at its Debian path
// (/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf, package fonts-dejavu-core, which
// tools/setup.sh installs). A missing or unreadable font is an Error naming the path and the
// package: a picture without its values would mislead, so none is written.
#pragma once
#include <cstdint>
#include <string>

#include "meshsal/meshsal.h"

namespace meshsal {

// The font file text is drawn with (see above).
std::string font_path();

// Width in pixels of `text` (UTF-8) at a line height of `px` pixels.
int text_width(const std::string& text, double px);

// `text` as it is when it fits in `width` pixels at px, else cut (at whole characters) and
// ended with "...".
std::string fit_text(const std::string& text, double px, int width);

// Draws `text` (UTF-8) with the top of its line at y and its left end at x (clipped to the image).
void draw_text(Image& img, int x, int y, const std::string& text, double px, const uint8_t rgb[3]);

}  // namespace meshsal
