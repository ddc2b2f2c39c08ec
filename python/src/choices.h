// meshsal Python module: the string options the CLI takes (--backend, --up), parsed for
// keyword arguments with ValueError naming the argument.
#pragma once
#include <string>

#include "meshsal/meshsal.h"

namespace meshsal_py {

// "auto", "cpu" or "gpu".
meshsal::Backend parse_backend(const std::string& name);

// "x", "y", "z", "-x", "-y", "-z" (also "+x"...).
meshsal::UpAxis parse_up(const std::string& name);

// The same rotation the library's camera applies for `up` (view/camera.cpp's table, which
// the public header describes: for z up, theta 0 looks from -y and phi 90 degrees from +z):
// the y-up angles of the search turned into the angles of `up`, as `meshsal viewpoint --up`
// prints them. `direction` receives the unit direction in the mesh's coordinates.
meshsal::ViewAngles angles_for_up(const meshsal::ViewAngles& y_up, meshsal::UpAxis up, double direction[3]);

}  // namespace meshsal_py

namespace meshsal_py {

// "exact", "fast" or "auto" (SaliencyOptions::method).
meshsal::Method parse_method(const std::string& name);

// "auto", "mixed" or "double" (SaliencyOptions::precision).
meshsal::Precision parse_precision(const std::string& name);

}  // namespace meshsal_py
