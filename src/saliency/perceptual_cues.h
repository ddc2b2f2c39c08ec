// meshsal: the perceptual model's cues that need no views (Model, meshsal/saliency.h;
// docs/method.md "The perceptual model"): height along the up axis and global rarity of a
// multi-scale curvature descriptor. Exposure is view/exposure.h; the combination is
// api/perceptual_model.cpp.
#pragma once
#include <cstdint>
#include <vector>

#include "meshsal/meshsal.h"

namespace meshsal {

// Height of every mesh point along `up` (a unit vector in the mesh's coordinates), 0 at
// the lowest mesh point and 1 at the highest; 0 for vertices that are not mesh points and
// everywhere when the points have no extent along `up`.
std::vector<double> height_cue(const Mesh& mesh, const std::vector<uint8_t>& is_point, const double up[3]);

// The descriptor's scales, in eps: each point is described by its mean curvature averaged
// (SPEC 1's Gaussian average) at 2, 4 and 8 eps, fine to coarse.
std::vector<double> rarity_descriptor_scales();

// Bins per descriptor dimension of global_rarity.
constexpr int kRarityBins = 8;

// Global rarity (self-information, Bruce & Tsotsos 2006; on meshes, Wu et al. 2013): each
// dimension of the points' descriptors (`columns[d][vertex]`) is cut into kRarityBins equal
// bins between its 0.5th and 99.5th percentile over the mesh points (values outside go to
// the end bins; a dimension with no spread there takes its minimum..maximum, and one with
// none at all a single bin), the joint bins are counted over the points, and a point gets
// -log(count of its bin / points): 0 for a descriptor every point shares, log(points) for
// one no other point has. 0 for vertices that are not mesh points.
std::vector<double> global_rarity(const std::vector<std::vector<double>>& columns, const std::vector<uint8_t>& is_point);

// `values` divided by their maximum over the mesh points (unchanged when that is not
// positive), 0 off the mesh points.
void scale_to_max(std::vector<double>& values, const std::vector<uint8_t>& is_point);

}  // namespace meshsal
