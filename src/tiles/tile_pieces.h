// meshsal (internal): the pieces of tiled simplification: a tile's sub-mesh cut out of a
// larger mesh with global vertex ids, and pieces put back together (simplify_tiled.cpp).
#pragma once
#include <cstdint>
#include <vector>

#include "meshsal/meshsal.h"

namespace meshsal {
namespace detail {

// One tile: what the per-tile step needs, and all it needs (an out-of-core driver can
// build it from the tile's triangles and the 1-ring around them).
struct TilePiece {
  Mesh mesh;                    // the tile's triangles, then `guards` triangles around it
  std::vector<uint32_t> ids;    // the global id of each vertex of `mesh`, increasing
  // Per vertex: shared with another tile, or a guard's corner. The simplifier neither
  // moves nor removes it, nor joins two of them by a new edge (another tile could make the
  // same edge: a non-manifold edge once joined).
  std::vector<uint8_t> pinned;
  // The last `guards` triangles of `mesh` are the other triangles at the pinned vertices.
  // All their corners are pinned, so they never change; they are there so that the
  // collapse checks see the whole neighbourhood of a pinned vertex (else a tile could make
  // an edge its neighbour already has: a non-manifold edge, or a triangle twice), and the
  // quadrics of a pinned vertex hold the planes on both sides.
  size_t guards = 0;
};

// Triangles per vertex (compressed rows): the triangles of vertex v are
// tri[start[v] .. start[v + 1]).
struct VertexTriangles {
  std::vector<uint32_t> start, tri;
};
VertexTriangles vertex_triangles(const Mesh& mesh);

// The piece of `mesh` made of its triangles `tile` (indices, increasing) with the guards
// around them: every triangle t with group[t] != group_id that shares a vertex with
// them (none when `around` is null). `ids`: the global id of each vertex of `mesh`
// (increasing).
TilePiece cut_piece(const Mesh& mesh, const std::vector<uint32_t>& ids, const VertexTriangles* around,
                    const std::vector<uint32_t>& group, uint32_t group_id, const std::vector<uint32_t>& tile);

// The per-tile step: tile.mesh simplified toward `target_faces` of its own triangles, its
// pinned vertices and guards kept as they are, borders as options.lock_border says.
// Returns the tile's triangles only (no guards), the vertices they use and their global
// ids. `weights`: one per vertex of tile.mesh (may be null). target_faces >= 1. `record`:
// report->sequence gets the collapses.
TilePiece simplify_tile(const TilePiece& tile, const std::vector<double>* weights, size_t target_faces,
                        const SimplifyOptions& options, SimplifyReport* report, bool record = false);

// The pieces as one mesh (no guards may be left in them): its vertices are the union of
// theirs in increasing global id (`ids` receives them), a vertex in several pieces taken
// from the first; the triangles piece by piece. Names (attributes, materials) and origin
// come from `like`.
Mesh merge_pieces(const std::vector<TilePiece>& pieces, const Mesh& like, std::vector<uint32_t>* ids);

}  // namespace detail
}  // namespace meshsal
