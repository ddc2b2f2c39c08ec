// meshsal: procedural test meshes (generated in code, no files needed).
#pragma once
#include <cstdint>
#include <vector>

#include "meshsal/meshsal.h"

namespace meshsal {

// Icosphere of the given radius, centred at the origin: 20 * 4^subdivisions triangles.
Mesh make_sphere(double radius, int subdivisions);

// Square plane z = 0 of side `size`, centred at the origin, n x n quads split in two.
Mesh make_plane(double size, int n);

// The plane with a smooth Gaussian bump of given height and width at its centre.
Mesh make_plane_with_bump(double size, int n, double height, double width);

// Closed unit cube [-1,1]^3, each face an n x n grid.
Mesh make_cube(int n);

// The demo mesh of the paper's point: a unit icosphere covered with ~900 regular small
// bumps and one unique larger, smoother feature. With 5+ subdivisions mean curvature rates
// the bumps at least as high as the feature, while saliency picks the feature. feature_mask (if given) marks the vertices of the
// unique feature, bump_mask those of the repeated bumps.
Mesh make_bumpy_sphere(int subdivisions, std::vector<uint8_t>* feature_mask = nullptr,
                       std::vector<uint8_t>* bump_mask = nullptr);

}  // namespace meshsal
