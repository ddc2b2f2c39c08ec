// meshsal: distances between two triangle surfaces (point-to-triangle over a BVH):
// symmetric Hausdorff and RMS distance, and the error of the salient region.
#pragma once
#include <cstdint>
#include <vector>

#include "meshsal/mesh.h"

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

// Distance from p to the closest triangle by testing every triangle (the test oracle).
double surface_distance_bruteforce(const Mesh& mesh, const double p[3]);

// Points on a surface: every mesh point (referenced vertex) followed by `face_samples`
// points spread over the triangles in proportion to their area (deterministic:
// error-diffusion allocation, an R2 low-discrepancy pattern inside each triangle). 3 per point.
std::vector<double> sample_surface(const Mesh& mesh, size_t face_samples);

struct CompareOptions {
  size_t face_samples = 200000;     // area samples per surface, on top of its vertices
  double salient_fraction = 0.30;   // top fraction of the original's mesh points by saliency
  unsigned threads = 0;             // 0 = all cores
};

struct SurfaceComparison {
  double diagonal = 0;          // bbox diagonal of the original's mesh points
  double forward_max = 0;       // original samples -> simplified surface
  double forward_rms = 0;
  double backward_max = 0;      // simplified samples -> original surface
  double backward_rms = 0;
  double hausdorff = 0;         // max(forward_max, backward_max)
  double rms = 0;               // max(forward_rms, backward_rms)
  double salient_error = -1;    // mean distance of the salient vertices; -1 without saliency
  size_t salient_vertices = 0;
  size_t forward_samples = 0, backward_samples = 0;
};

// Compares `simplified` with `original`. `saliency` (may be null): one value per vertex of
// the original; the top salient_fraction of its mesh points (ties: lower index first) give
// salient_error, the mean of their distances to the simplified surface.
// Throws Error when either mesh has no triangle or saliency has the wrong size.
SurfaceComparison compare_surfaces(const Mesh& original, const Mesh& simplified,
                                   const std::vector<double>* saliency,
                                   const CompareOptions& options = {});

// Mean distance to `surface` of the vertices of `mesh` with the top `fraction` of `saliency`
// (over mesh points; ties: lower index first). Returns it and the count used.
double salient_region_error(const Mesh& mesh, const std::vector<double>& saliency,
                            const TriangleBvh& surface, double fraction, size_t* count = nullptr);

}  // namespace meshsal
