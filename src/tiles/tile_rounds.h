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

// Rounds (tile_pass.h) until `target` faces or a round that gives up nothing: each a first
// pass on `tiles` tiles over `box`, then the strips along its cuts (strip_grid).
void run_rounds(TilePasses& passes, const BoundingBox& box, unsigned tiles, uint64_t target);

}  // namespace detail
}  // namespace meshsal
