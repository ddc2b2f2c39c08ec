// meshsal: what makes a picture readable: a colour bar with its values, title lines, and the
// panel layout that adds them around a rendered image.
#pragma once
#include <string>
#include <vector>

#include "io/colormap.h"
#include "meshsal/meshsal.h"

namespace meshsal {

// Text height in pixels for a picture `width` pixels wide (13..28).
double text_size_for(int width);

// Height of the band draw_colour_bar fills at text size px.
int colour_bar_height(double px);

// Draws in the band [y, y + colour_bar_height(px)) from x to x + w: `label` and ", square-root
// scale" (the label alone where both do not fit) above a horizontal
// bar running the colour scale from limits.lo (left) to limits.hi (right), five ticks with
// their values under it. The bar's pixels are the colour map's own (unshaded) colours.
void draw_colour_bar(Image& img, int x, int y, int w, const ColorLimits& limits,
                     const std::string& label, double px);

// Pixel column of value v on a bar drawn at x with width w.
int colour_bar_x(int x, int w, const ColorLimits& limits, double v);

// Height of the band of `lines` title lines at text size px (add_title_and_bar's top band).
int title_height(double px, int lines);

// `body` with `title` lines above it and, when bar is given, a colour bar (labelled) below;
// background white. Width: body's (at least the title's).
Image add_title_and_bar(const Image& body, const std::vector<std::string>& title,
                        const ColorLimits* bar, const std::string& bar_label);

// "%.3g" with no trailing noise, for values on pictures.
std::string value_text(double v);

}  // namespace meshsal
