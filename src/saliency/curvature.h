// meshsal: per-vertex normals and Taubin mean curvature (SPEC 1).
#pragma once
#include <vector>

#include "core/adjacency.h"
#include "core/mesh_points.h"
#include "meshsal/meshsal.h"

namespace meshsal {

// Area-weighted vertex normals (sum of un-normalised face normals, normalised);
// 3 doubles per vertex, zero where the sum vanishes. Each vertex's sum runs in triangle
// order on any thread count (the same bits).
std::vector<double> vertex_normals(const Mesh& mesh, unsigned threads = 0);

// Taubin mean curvature H_i = sum_j w_ij k_ij |T_ij|^2 per vertex; 0 for unreferenced
// vertices, for vertices whose normal vanishes and where all incident area is zero.
std::vector<double> mean_curvature(const Mesh& mesh, const Adjacency& adjacency,
                                   const std::vector<double>& normals, unsigned threads = 0);

// mean_curvature(mesh, build_adjacency(mesh), vertex_normals(mesh)) at the listed vertices
// alone, the same bits, into H[v] for each (the rest of H untouched): from the triangles
// that hold them, on a copy of those renumbered in the same relative order (so the
// neighbours sort alike and each sum runs in the same order). The GPU's exact curvature
// leaves a vertex of many triangles to the host this way.
void mean_curvature_at(const Mesh& mesh, const std::vector<uint32_t>& vertices, double* H, unsigned threads = 0);

// The same H from one pass over the triangles, without the 1-rings (the fast method's:
// build_adjacency is most of the curvature stage's time and memory on a large scan). Each
// edge's area is added triangle by triangle, so H differs from mean_curvature()'s in the
// last bits (tests: within 1e-12 relative); independent of the thread count.
std::vector<double> mean_curvature_faces(const Mesh& mesh, const std::vector<double>& normals,
                                         unsigned threads = 0);

// The fast method's curvature: vertex_normals and mean_curvature_faces on a copy of the
// mesh renumbered along a Morton curve over `box` (renumbered_mesh), H returned in input
// order. A scan's vertices in curve order and its triangles sorted with them make both
// passes read and add near in memory (igea_loop2 subdivided once: 1.3 s where its input
// order took 3.5 s). Each vertex sums its triangles in an order fixed by the relative
// order of the vertices alone, so a tile over the whole mesh's `box` (the mesh points'
// bounding box) gets its own vertices' H in the same bits as the whole mesh.
std::vector<double> mean_curvature_morton(const Mesh& mesh, const BoundingBox& box, unsigned threads = 0);

}  // namespace meshsal
