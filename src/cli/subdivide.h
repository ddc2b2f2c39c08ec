// meshsal: midpoint subdivision (each triangle into 4, one new vertex per edge), used by the
// benchmark to make meshes of ~10 million vertices from the largest scan in memory.
#pragma once
#include "meshsal/meshsal.h"

namespace meshsal {

// Every edge gets its midpoint as a new vertex (shared by the triangles on that edge); each
// triangle becomes four. Vertex count V + E, triangle count 4 T. Throws Error past 2^32 - 1
// vertices.
Mesh subdivide_midpoint(const Mesh& mesh);

}  // namespace meshsal
