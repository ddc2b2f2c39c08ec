// meshsal (internal): what every pass of tiled simplification does to one group, and the
// order of the passes; shared by the in-memory driver (simplify_tiled.cpp) and the
// out-of-core one (tiles/simplify_out_of_core.cpp), so that both make the same collapses.
#pragma once
#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

#include "meshsal/meshsal.h"
#include "tiles/tile_pieces.h"

namespace meshsal {
namespace detail {

// What a pass keeps of its groups' faces (pass_collapses); each group's share then comes
// from the common error level.
enum class Targets {
  FirstPass,  // the ratio on the triangles away from the cut; those at it stay (they wait for the strips)
  Remaining,  // a strip pass: the faces still over the round's target (to_remove)
};

struct PassBudget {
  Targets rule = Targets::FirstPass;
  double ratio = 1;        // FirstPass: the round's target / its faces
  long long to_remove = 0; // Remaining: faces still over the round's target
};

struct PassTotals {
  size_t collapses = 0, refused = 0;
  double error = 0;  // the largest collapse error, in model units
};

// Pass 1's goal for a group by the ratio: the ratio of its triangles away from the cut,
// and every triangle at it (two pinned corners: they wait for the strips).
size_t first_pass_goal(const TilePiece& tile, double ratio);

// One group: `tile` (its own triangles, then the guards) simplified toward `goal` faces of
// its own (level_goals); the totals move on. `weights`: one per vertex of tile.mesh (may
// be null).
TilePiece simplify_group(const TilePiece& tile, const std::vector<double>* weights, const SimplifyOptions& options,
                         size_t goal, PassTotals& totals);

// Rounds: each keeps at most this share of the faces it starts from (its first pass over
// every triangle, then its strips), so a round's cuts are at most twice as fine as its
// result. Measured (tests/tiles/test_simplify_tiled.cpp, igea_134k at 1%, 4 tiles): one round
// straight to the target left the cuts at full resolution, a strip pass had to remove
// 80% of what was left from bands a few triangles wide, and the RMS error was 3.5x the
// untiled run's; halving rounds: 1.1x.
constexpr double kRoundRatio = 0.5;
size_t round_target(size_t faces_now, size_t target);

// The error level of each collapse the tile would make on its way down to an eighth of
// its own faces: the largest collapse cost so far, in model units, so that the levels of
// all tiles compare. Each collapse removes two faces (the tiled path locks borders).
std::vector<double> collapse_levels(const TilePiece& tile, const std::vector<double>* weights,
                                    const SimplifyOptions& options);

// Every pass spends its face budget where the error is, as one simplification of the whole
// mesh would, instead of the same ratio (or share of the faces) in every group: a strip
// piece of five triangles at a plane's corner, told to give up one, gave up the corner
// (Hausdorff 15% of the diagonal). The groups together
// make the `collapses` cheapest collapses by level (pass_collapses),
// found as the common level (the collapses-th smallest of all groups' levels), every
// collapse under it, and the ties at it handed out in group order up to the count.
// The collapses a pass asks of its groups' `faces` own faces: down to the sum of their
// first_pass_goal()s (`first_goals`) in a first pass, down by budget.to_remove in a strip
// pass; two faces a collapse.
uint64_t pass_collapses(const PassBudget& budget, uint64_t faces, uint64_t first_goals);
struct LevelCount {
  size_t below = 0, at = 0;  // a group's collapses under the level, and at it
};
LevelCount count_level(const std::vector<double>& levels, double level);
// Each group's face target: faces[g] - 2 * its collapses, at least 1.
std::vector<size_t> level_goals(const std::vector<LevelCount>& counts, const std::vector<size_t>& faces,
                                uint64_t collapses);

// A pass's goal for each of its groups, from all of the above: the pass_collapses (at most
// `level_count`, the levels there are) go to the cheapest levels of all groups.
// `faces`: each group's own faces; `first_goals`: the sum of their first_pass_goal()s (a
// first pass); `levels(g)`: group g's collapse_levels, asked for more than once (a driver
// keeps them in memory or on disk).
std::vector<size_t> pass_goals(const PassBudget& budget, const std::vector<size_t>& faces, uint64_t first_goals,
                               uint64_t level_count, const std::function<std::vector<double>(size_t)>& levels);

// The global ids of the vertices `tile`'s own triangles use that it did not pin: no other
// group has them, so this pass freed them (they are no longer pending).
std::vector<uint32_t> freed_ids(const TilePiece& tile);

// The grid of strip pass `step` (0, 1, ...) after the first pass over `tiles` tiles:
// false when there is none left. The first kMaxStripPasses shift the grid by
// kStripShifts; then tiles twice as large, and so on up to one piece (tiles so small that
// a triangle spans several pin nearly every vertex on every grid).
bool strip_grid(unsigned tiles, int step, unsigned* grid_tiles, double* shift);

}  // namespace detail
}  // namespace meshsal
