// meshsal (internal): tiled simplification (simplify_mesh_tiled in meshsal.h): the passes
// over a mesh in memory. The per-tile step and the pieces are in tile_pieces.h, the grid
// in tile_grid.h.
#pragma once
#include <cstddef>

namespace meshsal {
namespace detail {

// The most tiles along the longest axis (1025^3 shifted cells still fit a 64-bit id).
constexpr unsigned kMaxSimplifyTiles = 1024;

// Strip passes after the first pass, at most, and the shift of each one's grid (in tiles):
// the first strips' cuts fall mid-way between the first pass's, the second's between
// both, so that a vertex the first two passes both had to pin (where their cuts cross)
// lies inside a strip; the third takes what is left.
constexpr int kMaxStripPasses = 3;
constexpr double kStripShifts[kMaxStripPasses] = {0.5, 0.25, 0.75};

// Rings of triangles a strip takes around the pinned vertices it frees: room for their
// collapses. 1 measured best (bunny_36k at 10%, sphere at 10% and 2%, 4 tiles): each
// strip pass starts its quadrics afresh from the surface the last pass left, so a wider
// strip re-simplifies more of it and loses more.
constexpr int kStripRings = 1;

}  // namespace detail
}  // namespace meshsal
