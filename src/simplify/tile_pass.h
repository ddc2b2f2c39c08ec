// meshsal (internal): what every pass of tiled simplification does to one group, and the
// order of the passes; shared by the in-memory driver (simplify_tiled.cpp) and the
// out-of-core one (api/simplify_out_of_core.cpp), so that both make the same collapses.
#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

#include "meshsal/meshsal.h"
#include "simplify/tile_pieces.h"

namespace meshsal {
namespace simplify_detail {

// How a pass sets each group's face target.
enum class Targets {
  FirstPass,  // the ratio on the triangles away from the cut; those at it stay (they wait for the strips)
  Remaining,  // the faces still over the target, spread over the groups by face count, carried on
};

// What a pass has left to do, carried from group to group in group order.
struct PassBudget {
  Targets rule = Targets::FirstPass;
  double ratio = 1;        // FirstPass: target / input faces
  long long to_remove = 0; // Remaining: faces still over the whole mesh's target
  size_t faces_left = 0;   // Remaining: selected faces not yet simplified
};

struct PassTotals {
  size_t collapses = 0, refused = 0;
  double error = 0;  // the largest collapse error, in model units
};

// One group: `tile` (its own triangles, then the guards) simplified toward the goal the
// budget gives it; the budget and the totals move on. `weights`: one per vertex of
// tile.mesh (may be null).
TilePiece simplify_group(const TilePiece& tile, const std::vector<double>* weights, const SimplifyOptions& options,
                         PassBudget& budget, PassTotals& totals);

// The global ids of the vertices `tile`'s own triangles use that it did not pin: no other
// group has them, so this pass freed them (they are no longer pending).
std::vector<uint32_t> freed_ids(const TilePiece& tile);

// The grid of strip pass `step` (0, 1, ...) after the first pass over `tiles` tiles:
// false when there is none left. The first kMaxStripPasses shift the grid by
// kStripShifts; then tiles twice as large, and so on up to one piece (tiles so small that
// a triangle spans several pin nearly every vertex on every grid).
bool strip_grid(unsigned tiles, int step, unsigned* grid_tiles, double* shift);

}  // namespace simplify_detail
}  // namespace meshsal
