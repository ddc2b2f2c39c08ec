// check_saliency_options(): the options every saliency path (CPU, GPU, every front end)
// checks before it computes; in the saliency layer, whose CPU path calls it itself.
#include <algorithm>
#include <cstdio>
#include <string>

#include "meshsal/meshsal.h"
#include "core/number_text.h"
#include "saliency/saliency.h"

namespace meshsal {

void check_saliency_options(const SaliencyOptions& options) {
  if (!(options.eps_frac > 0 && options.eps_frac <= kMaxEpsFrac))
    throw Error("eps-frac must be a finite number in (0, " + number_text(kMaxEpsFrac) + "], got " +
                number_text(options.eps_frac));
  if (options.scales.empty() || options.scales.size() > kMaxScaleCount)
    throw Error("scales: give 1 to " + std::to_string(kMaxScaleCount) + " scales, got " +
                std::to_string(options.scales.size()));
  double largest = 0;
  for (double k : options.scales) {
    if (!(k > 0 && k <= kMaxScale))
      throw Error("scales must be finite numbers in (0, " + number_text(kMaxScale) + "], got " + number_text(k));
    largest = std::max(largest, k);
  }
  // The surround Gaussian 2k eps wider than the whole mesh averages everything alike: the
  // center-surround maps would be ~0 (what `--scales 1e300` gave).
  if (2 * largest * options.eps_frac > 1)
    throw Error("scales and eps-frac: the widest surround sigma, 2 x " + number_text(largest) +
                " x " + number_text(options.eps_frac) +
                " of the bounding-box diagonal, must be at most 1 diagonal");
  // Tiles per axis cube into up to tiles^3 tiles, each a pass over the mesh in memory.
  if (options.tiles > kMaxTiles)
    throw Error("tiles must be at most " + std::to_string(kMaxTiles) + " along the longest axis, got " +
                std::to_string(options.tiles));
}

}  // namespace meshsal
