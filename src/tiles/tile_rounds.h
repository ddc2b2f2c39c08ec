// meshsal (internal): the rounds of tiled simplification, written once for both drivers:
// the mesh in memory (simplify_tiled.cpp) and the mesh on disk (simplify_out_of_core.cpp).
// A driver says how to run one pass over its mesh (TilePasses); run_rounds decides which
// passes run, on which grid, toward which budget, so both make the same collapses.
#pragma once
#include <cstdint>

#include "meshsal/meshsal.h"
#include "tiles/tile_grid.h"
#include "tiles/tile_pass.h"

namespace meshsal {
namespace detail {

// One driver's passes over its mesh.
class TilePasses {
 public:
  virtual ~TilePasses() = default;
  // The mesh's triangles now.
  virtual uint64_t triangles() const = 0;
  // A first pass: every vertex pending, every triangle selected, grouped by `grid`.
  virtual void first_pass(const TileGrid& grid, const PassBudget& budget) = 0;
  // A strip pass: the triangles around the vertices still pending, grouped by `grid`.
  // Returns false, having run nothing, when no strip is left.
  virtual bool strip_pass(const TileGrid& grid, const PassBudget& budget) = 0;
};

// A round's tiles along the longest axis: `tiles`, or fewer where its goal would leave a
// tile fewer than about kRoundTileFaces output faces (a surface meets ~t^2 of a t^3 grid's
// cubes), so the last rounds of a small target run in a few large tiles: tiles a few output
// triangles wide pin most of their vertices. Measured at 1% (RMS over the untiled run's,
// plain / balanced): bunny_36k with 8 tiles 3.32x / 2.40x before, 0.81x / 0.74x with 1000
// (500: 0.81x / 0.75x; 2000: 0.84x / 0.79x); igea_134k with 8 tiles 2.13x / 1.65x before,
// 0.81x / 0.80x. The memory a tile needs only falls: a round's mesh is about twice its goal.
constexpr uint64_t kRoundTileFaces = 1000;
unsigned round_tiles(unsigned tiles, uint64_t goal);

// Rounds (tile_pass.h) until `target` faces or a round that gives up nothing: each a first
// pass on `tiles` tiles over `box`, then the strips along its cuts (strip_grid).
void run_rounds(TilePasses& passes, const BoundingBox& box, unsigned tiles, uint64_t target);

}  // namespace detail
}  // namespace meshsal
