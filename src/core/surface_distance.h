// meshsal: distances between two triangle surfaces (point-to-triangle over a BVH):
// symmetric Hausdorff and RMS distance, and the error of the salient region.
#pragma once
#include <cstdint>
#include <vector>

#include "meshsal/meshsal.h"

namespace meshsal {

// Squared distance from p to triangle (a, b, c) (closest point by Voronoi regions,
// Ericson, Real-Time Collision Detection 5.1.5). Degenerate triangles work too.
double point_triangle_distance_sq(const double p[3], const double a[3], const double b[3],
                                  const double c[3]);

// Bounding volume hierarchy over a mesh's triangles (median split on the widest axis of
// the centroids, up to 4 triangles a leaf) for closest-point queries.
struct TriangleBvh {
  struct Node {
    double lo[3], hi[3];
    uint32_t first;  // leaf: first index into `order`; inner: index of the left child
    uint32_t count;  // leaf: number of triangles (> 0); inner: 0 (right child = first + 1)
  };
  std::vector<Node> nodes;
  std::vector<uint32_t> order;   // triangle indices, grouped by leaf
  std::vector<double> corners;   // 9 per entry of `order`: the triangle's corners
};

// Throws Error when the mesh has no triangle.
TriangleBvh build_triangle_bvh(const Mesh& mesh);

// Distance from p to the closest point of the surface.
double surface_distance(const TriangleBvh& bvh, const double p[3]);

// The closest triangle to p and its distance: the index into the mesh's triangles (of
// ties, the lowest), for a value carried from the nearest point (transfer_nearest: each
// point a degenerate triangle).
struct ClosestTriangle {
  double distance = 0;
  uint32_t triangle = 0;
};
ClosestTriangle closest_triangle(const TriangleBvh& bvh, const double p[3]);

// Distance from p to the closest triangle by testing every triangle (the test oracle).
double surface_distance_bruteforce(const Mesh& mesh, const double p[3]);

// Points on a surface: every mesh point (referenced vertex) followed by `face_samples`
// points spread over the triangles in proportion to their area (deterministic:
// error-diffusion allocation, an R2 low-discrepancy pattern inside each triangle). 3 per point.
std::vector<double> sample_surface(const Mesh& mesh, size_t face_samples);

// Mean distance to `surface` of the vertices of `mesh` with the top `fraction` of `saliency`
// (over mesh points; ties: lower index first). Returns it and the count used.
double salient_region_error(const Mesh& mesh, const std::vector<double>& saliency,
                            const TriangleBvh& surface, double fraction, size_t* count = nullptr);

}  // namespace meshsal
