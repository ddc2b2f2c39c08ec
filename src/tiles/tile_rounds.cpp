#include "tiles/tile_rounds.h"

#include <algorithm>
#include <cmath>

namespace meshsal {
namespace detail {

unsigned round_tiles(unsigned tiles, uint64_t goal) {
  const double by_faces = std::floor(std::sqrt(double(goal) / double(kRoundTileFaces)));
  return unsigned(std::clamp(by_faces, 1.0, double(std::max(1u, tiles))));
}

void run_rounds(TilePasses& passes, const BoundingBox& box, unsigned tiles_given, uint64_t target) {
  for (uint64_t now = passes.triangles(); now > target; now = passes.triangles()) {
    const uint64_t goal = round_target(size_t(now), size_t(target));
    const unsigned tiles = round_tiles(tiles_given, goal);
    PassBudget first;
    first.ratio = double(goal) / double(now);
    passes.first_pass(TileGrid(box, tiles, 0), first);
    unsigned grid_tiles = 0;
    double shift = 0;
    for (int step = 0; passes.triangles() > goal && strip_grid(tiles, step, &grid_tiles, &shift); ++step) {
      PassBudget rest;
      rest.rule = Targets::Remaining;
      rest.to_remove = (long long)passes.triangles() - (long long)goal;
      if (!passes.strip_pass(TileGrid(box, grid_tiles, shift), rest)) break;
    }
    if (passes.triangles() >= now) break;  // the round gave up nothing: neither will the next
  }
}

}  // namespace detail
}  // namespace meshsal
