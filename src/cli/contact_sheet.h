// meshsal batch: the contact sheet, one PNG of the models' best-view pictures, each shrunk
// to a thumbnail with its name under it. Layout: ceil(sqrt(n)) columns, cells of
// kSheetThumb x (kSheetThumb + kSheetLabel) pixels (the picture shrunk to fit the square,
// centred; the name centred in the band under it, shortened with "..." when too long)
// with kSheetGap pixels around and between them, on white.
#pragma once
#include <string>
#include <vector>

#include "meshsal/meshsal.h"

namespace meshsal_cli {

constexpr int kSheetThumb = 256;
constexpr int kSheetLabel = 28;
constexpr int kSheetGap = 8;

struct SheetItem {
  std::string name;  // shown under the thumbnail
  std::string png;   // the best-view picture to shrink
};

// Throws meshsal::Error "PNG: cannot read the picture" for a file it cannot decode, and
// for an empty list.
meshsal::Image contact_sheet(const std::vector<SheetItem>& items);

}  // namespace meshsal_cli
