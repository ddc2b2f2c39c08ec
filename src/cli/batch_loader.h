// meshsal batch: reads the next model on a thread of its own while the current one
// computes. One model ahead at most: memory holds the current mesh and the next one.
#pragma once
#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "meshsal/meshsal.h"

namespace meshsal::cli {

struct LoadedModel {
  std::string path;
  meshsal::Mesh mesh;
  std::string error;        // the one-line message when loading failed ("" = loaded)
  double seconds = 0;       // time spent reading and parsing
  uint64_t welded_corners = 0;
  // With ModelLoader's `attributes`, for every format but STL: the file read again as
  // `meshsal simplify` reads it (LoadOptions::attributes: vt/vn, PLY properties, a glTF's
  // channels and materials, split at UV seams), for the simplified mesh; `mesh` stays as
  // `meshsal saliency` reads it. Its own message when that failed.
  bool has_attributed = false;
  meshsal::Mesh attributed;
  std::string attributed_error;
};

class ModelLoader {
 public:
  // Starts reading paths[0] at once. `attributes`: also LoadedModel::attributed.
  ModelLoader(std::vector<std::string> paths, bool attributes);
  ~ModelLoader();  // stops after the model being read, if any
  ModelLoader(const ModelLoader&) = delete;
  ModelLoader& operator=(const ModelLoader&) = delete;

  // The next model in order (waits for it), and the reading of the one after begins.
  // Call at most paths.size() times.
  LoadedModel next();

 private:
  void run();
  std::vector<std::string> paths_;
  bool attributes_;
  std::mutex mutex_;
  std::condition_variable changed_;
  std::optional<LoadedModel> ready_;  // the one slot
  bool stop_ = false;
  std::thread thread_;
};

}  // namespace meshsal::cli
