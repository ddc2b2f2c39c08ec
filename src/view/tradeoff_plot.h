// meshsal: the simplification trade-off plot of `meshsal bench --simplify --plot`: per model
// and ratio a panel of salient-region error against RMS error, both relative to plain
// quadrics, with axes, tick values, the target region and one legend.
#pragma once
#include <string>
#include <vector>

#include "meshsal/meshsal.h"

namespace meshsal {

struct TradeoffPoint {
  double x;  // RMS error / plain's
  double y;  // salient-region error / plain's
};

// The series every panel has, in legend order: the sweep of each curve (small dots), then
// the named methods (large markers). Plain quadrics are the point (1, 1) of every panel.
enum TradeoffSeries {
  kSweepThreshold, kSweepRank, kSweepContinuous, kPaperRecipe, kBalancedPreset, kMeshoptimizer,
  kTradeoffSeriesCount
};

// Legend text of each series.
const char* tradeoff_series_name(int series);

struct TradeoffPanel {
  std::string title;
  std::vector<TradeoffPoint> series[kTradeoffSeriesCount];
};

// Panels in rows of two, the legend under them; the target region (x <= target.x,
// y <= target.y) shaded. Axis ranges per panel cover its points, (1, 1) and the target.
Image tradeoff_plot(const std::vector<TradeoffPanel>& panels, TradeoffPoint target);

// Panel geometry, for the tests: size of one panel and the plot area inside it.
constexpr int kPanelWidth = 440, kPanelHeight = 330;
constexpr int kPlotLeft = 62, kPlotTop = 30, kPlotRight = 16, kPlotBottom = 48;

// Colour of each series (also the legend's swatch).
void tradeoff_series_colour(int series, uint8_t rgb[3]);

}  // namespace meshsal
