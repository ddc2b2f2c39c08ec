// meshsal batch --html: DIR/index.html, the gallery of a run's models.
#pragma once
#include <string>
#include <vector>

namespace meshsal::cli {

struct GalleryItem {
  std::string name;     // the input's file name
  std::string page;     // its viewer page, relative to the gallery ("" when none)
  std::string picture;  // its best-view picture, relative to the gallery ("" when none)
  std::string status;   // "done", "skipped" or "failed"
  std::string message;  // why, for the others
};

// One self-contained HTML file: a card per model, its thumbnail opening its page, or the
// model marked with its status and message. Written atomically; throws Error.
void write_gallery(const std::string& path, const std::vector<GalleryItem>& items);

}  // namespace meshsal::cli
