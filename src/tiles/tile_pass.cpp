// meshsal (internal): one group of a tiled simplification pass, see tile_pass.h.
#include "tiles/tile_pass.h"

#include <algorithm>
#include <cmath>

#include "core/mesh_points.h"
#include "core/streamed_percentile.h"
#include "tiles/simplify_tiled.h"

namespace meshsal {
namespace detail {

size_t first_pass_goal(const TilePiece& tile, double ratio) {
  // A triangle with two pinned corners lies on the cut: pass 1 cannot remove it (about
  // one per cut edge stays for the strips), so the ratio applies to the rest.
  const size_t f = tile.mesh.triangle_count() - tile.guards;
  size_t at_cut = 0;
  for (size_t t = 0; t < f; ++t) {
    const uint32_t* v = &tile.mesh.triangles[3 * t];
    at_cut += tile.pinned[v[0]] + tile.pinned[v[1]] + tile.pinned[v[2]] >= 2;
  }
  return at_cut + size_t(std::llround(ratio * double(f - at_cut)));
}

TilePiece simplify_group(const TilePiece& tile, const std::vector<double>* weights, const SimplifyOptions& options,
                         size_t goal, PassTotals& totals) {
  SimplifyReport rep;
  TilePiece out = simplify_tile(tile, weights, std::max<size_t>(goal, 1), options, &rep);
  totals.collapses += rep.collapses;
  totals.refused += rep.refused;
  // rep.error is in units of the tile's diagonal: to model units.
  const BoundingBox tb = bounding_box(tile.mesh.positions.data(), tile.mesh.vertex_count(), nullptr);
  totals.error = std::max(totals.error, rep.error * tb.diagonal());
  return out;
}

size_t round_target(size_t faces_now, size_t target) {
  return std::max(target, size_t(double(faces_now) * kRoundRatio));
}

std::vector<double> collapse_levels(const TilePiece& tile, const std::vector<double>* weights,
                                    const SimplifyOptions& options) {
  SimplifyReport rep;
  const size_t own = tile.mesh.triangle_count() - tile.guards;
  simplify_tile(tile, weights, std::max<size_t>(1, own / 4), options, &rep, true);
  // The simplifier's costs are in the tile's frame scaled to unit diagonal: quadric errors
  // scale with the fourth power of length.
  const BoundingBox tb = bounding_box(tile.mesh.positions.data(), tile.mesh.vertex_count(), nullptr);
  const double d2 = tb.diagonal() * tb.diagonal(), unit = d2 * d2;
  std::vector<double> levels(rep.sequence.size());
  double level = 0;
  for (size_t i = 0; i < levels.size(); ++i) levels[i] = level = std::max(level, rep.sequence[i].cost * unit);
  return levels;
}

uint64_t pass_collapses(const PassBudget& budget, uint64_t faces, uint64_t first_goals) {
  const uint64_t keep = budget.rule == Targets::FirstPass
                            ? first_goals
                            : faces - std::min<uint64_t>(faces, uint64_t(std::max(0LL, budget.to_remove)));
  return faces > keep ? (faces - keep) / 2 : 0;
}

LevelCount count_level(const std::vector<double>& levels, double level) {
  LevelCount c;
  c.below = size_t(std::lower_bound(levels.begin(), levels.end(), level) - levels.begin());
  c.at = size_t(std::upper_bound(levels.begin(), levels.end(), level) - levels.begin()) - c.below;
  return c;
}

std::vector<size_t> level_goals(const std::vector<LevelCount>& counts, const std::vector<size_t>& faces,
                                uint64_t collapses) {
  uint64_t below = 0;
  for (const LevelCount& c : counts) below += c.below;
  uint64_t ties = collapses > below ? collapses - below : 0;
  std::vector<size_t> goals(faces.size());
  for (size_t g = 0; g < faces.size(); ++g) {
    const size_t take = size_t(std::min<uint64_t>(ties, counts[g].at));
    ties -= take;
    const size_t n = counts[g].below + take;
    goals[g] = faces[g] > 2 * n + 1 ? faces[g] - 2 * n : 1;
  }
  return goals;
}

std::vector<uint32_t> freed_ids(const TilePiece& tile) {
  // tile.ids increases with the local index: the freed ids come out increasing.
  const size_t own = tile.mesh.triangles.size() - 3 * tile.guards;
  std::vector<uint8_t> used(tile.ids.size(), 0);
  for (size_t i = 0; i < own; ++i) used[tile.mesh.triangles[i]] = 1;
  std::vector<uint32_t> ids;
  for (size_t v = 0; v < used.size(); ++v)
    if (used[v] && !tile.pinned[v]) ids.push_back(tile.ids[v]);
  return ids;
}

bool strip_grid(unsigned tiles, int step, unsigned* grid_tiles, double* shift) {
  if (step < kMaxStripPasses) {
    *grid_tiles = tiles;
    *shift = kStripShifts[step];
    return true;
  }
  unsigned t = tiles / 2;
  for (int s = kMaxStripPasses; s < step && t >= 1; ++s) t /= 2;
  if (t < 1) return false;
  *grid_tiles = t;
  *shift = t == 1 ? 0 : 0.5;
  return true;
}

std::vector<size_t> pass_goals(const PassBudget& budget, const std::vector<size_t>& faces, uint64_t first_goals,
                               uint64_t level_count, const std::function<std::vector<double>(size_t)>& levels) {
  uint64_t own = 0;
  for (size_t f : faces) own += f;
  const uint64_t collapses = std::min(pass_collapses(budget, own, first_goals), level_count);
  const ValueStream all = [&](const std::function<void(double)>& take) {
    for (size_t g = 0; g < faces.size(); ++g)
      for (double x : levels(g)) take(x);
  };
  const double level = collapses == 0 ? -1.0 : streamed_kth(all, collapses - 1);
  std::vector<LevelCount> counts;
  for (size_t g = 0; g < faces.size(); ++g) counts.push_back(count_level(levels(g), level));
  return level_goals(counts, faces, collapses);
}

}  // namespace detail
}  // namespace meshsal
