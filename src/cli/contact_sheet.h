// meshsal batch: the contact sheet, one PNG with a tile for every model of the run: its
// best-view picture shrunk to a thumbnail, or for a model that failed (or was not read) a
// grey tile marked with a red cross and "failed" (or "skipped"), and its message; each with
// its name under it. Layout: ceil(sqrt(n)) columns, cells of kSheetThumb x (kSheetThumb +
// kSheetLabel) pixels (the picture shrunk to fit the square, centred; the name centred in
// the band under it at kSheetLabelPx, shortened with "..." when too long) with kSheetGap
// pixels around and between them, on white.
#pragma once
#include <string>
#include <vector>

#include "meshsal/meshsal.h"

namespace meshsal::cli {

constexpr int kSheetThumb = 256;
constexpr int kSheetLabel = 34;
constexpr int kSheetGap = 8;
constexpr double kSheetLabelPx = 24;  // the names' line height (capitals about 15 px tall)

// The failed tile's colours.
constexpr uint8_t kSheetTileGrey[3] = {232, 232, 232};
constexpr uint8_t kSheetCrossRed[3] = {210, 40, 40};

struct SheetItem {
  std::string name;     // shown under the tile
  std::string png;      // the best-view picture to shrink; "" for a model without one:
  std::string status;   // then "failed" (a red cross) or "skipped"
  std::string message;  // and why, wrapped on the tile (at most 5 lines, shortened with "...")
};

// Throws meshsal::Error "PNG: cannot read the picture" for a file it cannot decode, and
// for an empty list.
meshsal::Image contact_sheet(const std::vector<SheetItem>& items);

}  // namespace meshsal::cli
