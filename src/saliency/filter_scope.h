// meshsal: what a Gaussian filter needs to run on one tile of a larger mesh (tiled saliency,
// saliency_tiles.h) and give the whole mesh's values at the tile's query vertices.
#pragma once
#include <cstdint>
#include <functional>
#include <vector>

#include "saliency/spatial_grid.h"

namespace meshsal {

struct FilterScope {
  // The whole mesh's mesh points: the grids (and the fast method's cells) are laid over
  // them, so a tile's sweep visits the same points in the same order as the whole mesh's.
  GridFrame frame;
  // Per vertex of the tile: 1 where the averages are wanted (null: at every mesh point).
  // Other vertices only contribute their values; their outputs are left 0 (the exact
  // sweep) or unspecified (the fast method's cells extrapolate to every vertex they hold).
  const std::vector<uint8_t>* query = nullptr;
  // The fast method only: per sigma, the whole mesh's occupied cells of sigma /
  // cells_per_sigma (count_fast_cells), which decide between per-cell and per-vertex sums.
  // Without a query mask it may be empty: this mesh's own (the whole mesh filtered a sigma
  // at a time passes the scope only so that its box is found once).
  std::vector<uint64_t> occupied_cells;
  // The fast method: each sigma's averages handed over as soon as they are found (the
  // sigma's index, then the array: valid at the query vertices) instead of returned, one
  // sigma's array held at a time (a tile's halo then holds one average, not one per sigma).
  // Empty: returned.
  std::function<void(size_t, const std::vector<double>&)> take;
};

}  // namespace meshsal
