// meshsal (internal): one group of a tiled simplification pass, see tile_pass.h.
#include "simplify/tile_pass.h"

#include <algorithm>
#include <cmath>

#include "core/mesh_points.h"
#include "simplify/simplify_tiled.h"

namespace meshsal {
namespace simplify_detail {

TilePiece simplify_group(const TilePiece& tile, const std::vector<double>* weights, const SimplifyOptions& options,
                         PassBudget& budget, PassTotals& totals) {
  const size_t f = tile.mesh.triangle_count() - tile.guards;
  size_t goal;
  if (budget.rule == Targets::FirstPass) {
    // A triangle with two pinned corners lies on the cut: pass 1 cannot remove it (about
    // one per cut edge stays for the strips), so the ratio applies to the rest.
    size_t at_cut = 0;
    for (size_t t = 0; t < f; ++t) {
      const uint32_t* v = &tile.mesh.triangles[3 * t];
      at_cut += tile.pinned[v[0]] + tile.pinned[v[1]] + tile.pinned[v[2]] >= 2;
    }
    goal = at_cut + size_t(std::llround(budget.ratio * double(f - at_cut)));
  } else {
    const double share = budget.faces_left > 0
                             ? double(std::max(0LL, budget.to_remove)) * double(f) / double(budget.faces_left)
                             : 0;
    goal = f - std::min(f, size_t(std::llround(share)));
  }
  goal = std::max<size_t>(goal, 1);
  SimplifyReport rep;
  TilePiece out = simplify_tile(tile, weights, goal, options, &rep);
  totals.collapses += rep.collapses;
  totals.refused += rep.refused;
  // rep.error is in units of the tile's diagonal: to model units.
  const BoundingBox tb = bounding_box(tile.mesh.positions.data(), tile.mesh.vertex_count(), nullptr);
  totals.error = std::max(totals.error, rep.error * tb.diagonal());
  budget.to_remove -= (long long)f - (long long)out.mesh.triangle_count();
  budget.faces_left -= f;
  return out;
}

std::vector<uint32_t> freed_ids(const TilePiece& tile) {
  const size_t own = tile.mesh.triangles.size() - 3 * tile.guards;
  std::vector<uint32_t> ids;
  for (size_t i = 0; i < own; ++i) {
    const uint32_t v = tile.mesh.triangles[i];
    if (!tile.pinned[v]) ids.push_back(tile.ids[v]);
  }
  std::sort(ids.begin(), ids.end());
  ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
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

}  // namespace simplify_detail
}  // namespace meshsal
