// meshsal: the view map as a figure: render_view_map's plot with theta and phi axes and
// ticks, a colour bar of U and a legend for its two markers.
#pragma once
#include <string>

#include "meshsal/meshsal.h"

namespace meshsal {

// The plot (width x width/2, render_view_map) with phi ticks (90..-90 every 30 degrees) on
// the left, theta ticks (-180..180 every 60) below, axis names, a title line, the colour bar
// of U (the map's minimum to maximum) and a legend: the ring (`ring`, labelled ring_label)
// and the cross (`cross`, cross_label). Angles in the frame of `up` (as --theta/--phi).
Image view_map_picture(const ViewMap& map, int width, const ViewAngles& ring, const std::string& ring_label,
                       const ViewAngles& cross, const std::string& cross_label, const std::string& title);

}  // namespace meshsal
