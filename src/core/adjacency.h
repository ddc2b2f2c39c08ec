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

// Builds the 1-ring of every vertex from the triangles, on `threads` threads (0 = all
// cores). Neighbour lists are sorted and free of duplicates and of the vertex itself
// (degenerate triangles add no self edge). An edge's area sums its triangles' areas in
// triangle order, so the result does not depend on the thread count.
Adjacency build_adjacency(const Mesh& mesh, unsigned threads = 0);

// The same from one sorted list of all half-edges, serially: the oracle the tests hold
// build_adjacency to.
Adjacency build_adjacency_reference(const Mesh& mesh);

}  // namespace meshsal
