// meshsal: vertex 1-ring adjacency as CSR, with the area of the triangles on each edge.
#pragma once
#include <cstdint>
#include <vector>

#include "meshsal/meshsal.h"

namespace meshsal {

struct Adjacency {
  std::vector<uint32_t> offsets;    // vertex_count + 1 entries
  std::vector<uint32_t> neighbors;  // neighbours of v: neighbors[offsets[v] .. offsets[v+1])
  std::vector<double> edge_area;    // total area of the triangles containing edge (v, neighbour)
};

// Builds the 1-ring of every vertex from the triangles. Neighbour lists are sorted
// and free of duplicates and of the vertex itself (degenerate triangles add no self edge).
Adjacency build_adjacency(const Mesh& mesh);

}  // namespace meshsal
