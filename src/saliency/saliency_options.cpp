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
  if (options.model != Model::Lee2005) {
    if (options.tiles > 1 || options.exchange)
      throw Error(std::string("model ") + model_name(options.model) +
                  " runs in memory, in one piece: not with tiles (it needs every view of the whole mesh)");
    // Coarse scales are twice the given ones, within the same limits.
    if ((options.model == Model::Perceptual || options.model == Model::Coarse) &&
        (2 * largest > kMaxScale || 4 * largest * options.eps_frac > 1))
      throw Error(std::string("model ") + model_name(options.model) + " takes the saliency at twice the scales: the largest, " +
                  number_text(largest) + ", must be at most " + number_text(std::min(kMaxScale / 2, 1 / (4 * options.eps_frac))) +
                  " here");
  }
}

}  // namespace meshsal

namespace meshsal {

// The models' names (text.h): here, below every layer that names them in a message.
Model parse_model(const std::string& name) {
  if (name == "lee2005") return Model::Lee2005;
  if (name == "perceptual") return Model::Perceptual;
  if (name == "exposure") return Model::Exposure;
  if (name == "centre" || name == "center") return Model::Centre;
  if (name == "height") return Model::Height;
  if (name == "rarity") return Model::Rarity;
  if (name == "coarse") return Model::Coarse;
  throw Error("model must be lee2005, perceptual, exposure, centre, height, rarity or coarse, got '" + name + "'");
}

const char* model_name(Model model) {
  switch (model) {
    case Model::Lee2005: return "lee2005";
    case Model::Perceptual: return "perceptual";
    case Model::Exposure: return "exposure";
    case Model::Centre: return "centre";
    case Model::Height: return "height";
    case Model::Rarity: return "rarity";
    case Model::Coarse: return "coarse";
  }
  return "?";
}

}  // namespace meshsal
