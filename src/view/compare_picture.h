// meshsal: the comparison picture of `render --compare` and the demo: original | plain |
// saliency-weighted simplification, from one camera, each panel labelled, the simplified
// ones coloured by their distance to the original on one shared colour bar.
#pragma once
#include <string>
#include <vector>

#include "meshsal/meshsal.h"

namespace meshsal {

// Distance of every vertex of `mesh` to the surface of `original` (0 for non-points).
std::vector<double> distance_to(const Mesh& mesh, const Mesh& original);

// Three panels side by side (style.size each, 4 px apart) from `view` (style.up up), framed
// by the original's projected extent. Panel titles: "original: F faces", "PLAIN_NAME: F faces" and
// "SALIENT_NAME: F faces" (e.g. the files' names), with "RMS R%, Hausdorff H%" and, when
// `saliency` is given, "salient-region error E%" under the simplified ones: the numbers of
// compare_surfaces (meshsal compare), in % of the original's bounding-box diagonal. The original is coloured by saliency (grey when
// null) with its colour bar under it; the simplified panels by their vertices' distance to
// the original surface, 0 .. the larger maximum of the two, with that bar under both.
Image compare_picture(const Mesh& original, const std::vector<double>* saliency, const Mesh& plain,
                      const Mesh& salient, const ViewAngles& view, const RenderStyle& style,
                      const std::string& title, const std::string& plain_name = "plain",
                      const std::string& salient_name = "saliency-weighted");

}  // namespace meshsal
