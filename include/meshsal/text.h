// meshsal public interface: options as text: the parsers (parse_*) every front end reads its
// options with, and the names they read (*_name).
// Part of meshsal.h (which includes every part); the conventions at the top of
// meshsal.h hold for every function here.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "meshsal/device.h"
#include "meshsal/saliency.h"
#include "meshsal/simplify.h"
#include "meshsal/view.h"

namespace meshsal {

// A size as every front end reads it ("700M", "2G", "1.5G", "512K", "700MB", "2000000"): a
// decimal number with an optional K, M, G or T (powers of 1024, either case, a B after it
// allowed), truncated to whole bytes. Error on anything else: 0 bytes after truncation, more
// than 64 bits hold, hex, inf, a sign, an exponent, and a bare number under 1M (surely a
// forgotten unit: the message suggests it).
uint64_t parse_memory_size(const std::string& text);

// "auto", "mixed" or "double"; throws Error on anything else.
Precision parse_precision(const std::string& name);

// "exact", "fast" or "auto"; throws Error on anything else.
Method parse_method(const std::string& name);

// "auto", "cpu" or "gpu"; throws Error on anything else.
Backend parse_backend(const std::string& name);

// "lee2005", "perceptual", "exposure", "centre" (or "center"), "height", "rarity" or
// "coarse"; throws Error on anything else.
Model parse_model(const std::string& name);

// The names the parsers above read, for each value (the front ends' option texts).
const char* precision_name(Precision precision);
const char* method_name(Method method);
const char* backend_name(Backend backend);
const char* model_name(Model model);

// Parses "2,3,4,5,6" into scales; throws Error on anything else (empty, <= 0, > 100, junk).
std::vector<double> parse_scales(const std::string& text);

// "none", "saliency" or "balanced"; throws Error on anything else.
Weighting parse_weighting(const std::string& name);

// The name parse_weighting() reads: "none", "saliency" or "balanced".
const char* weighting_name(Weighting weighting);

// The levels of "0.5,0.2,0.05" or "20000,5000" (--lod): a number with a decimal point or
// an exponent is a ratio in (0, 1), a whole number a face count; all ratios or all counts
// (which of 0.5 and 300 has fewer faces depends on the mesh), each below the one before, at
// most 16. Error otherwise, so a bad list is found before any mesh is read.
std::vector<SimplifyOptions> parse_lod_levels(const std::string& text);

// "x", "y", "z", "-x", "-y" or "-z" (also "+x", "+y", "+z"); throws Error otherwise.
UpAxis parse_up_axis(const std::string& name);

// "MIN,MAX" in degrees (e.g. "0,60": from the horizon to 60 degrees above it); throws Error
// naming the problem (not two numbers, outside [-90, 90], min > max).
ElevationRange parse_elevation_range(const std::string& text);

// "LO,HI", each a number (a value) or a number followed by % (a percentile, 0..100), e.g.
// "0,0.5" or "5%,99%". Throws Error naming the problem (both values: lo < hi needed).
ColorRange parse_color_range(const std::string& text);

// "saliency" or "curvature"; throws Error on anything else.
Score parse_score(const std::string& name);

}  // namespace meshsal
