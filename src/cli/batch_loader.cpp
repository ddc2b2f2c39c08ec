// meshsal batch: ModelLoader (see batch_loader.h).
#include "batch_loader.h"

#include <new>

#include "core/timer.h"
#include "load_input.h"

namespace meshsal::cli {

ModelLoader::ModelLoader(std::vector<std::string> paths, bool attributes)
    : paths_(std::move(paths)), attributes_(attributes) {
  thread_ = std::thread([this] { run(); });
}

ModelLoader::~ModelLoader() {
  {
    std::lock_guard<std::mutex> g(mutex_);
    stop_ = true;
  }
  changed_.notify_all();
  thread_.join();
}

void ModelLoader::run() {
  for (const std::string& path : paths_) {
    {  // the slot is free before reading starts: never more than one model ahead
      std::unique_lock<std::mutex> l(mutex_);
      changed_.wait(l, [this] { return stop_ || !ready_; });
      if (stop_) return;
    }
    LoadedModel m;
    m.path = path;
    const meshsal::Timer t;
    try {
      meshsal::LoadedMesh read = load_input_mesh(path, false, true);  // as `meshsal saliency` reads it
                                                                       // (but never waits on a pipe)
      m.mesh = std::move(read.mesh);
      m.welded_corners = read.report.welded_corners;
      // STL holds no attributes: the same mesh either way. Every other format may (a glTF's
      // UVs and materials, an OFF's colours): read again with them, as `meshsal simplify` does.
      if (attributes_ && mesh_extension(path) != ".stl") {
        m.has_attributed = true;
        try {
          m.attributed = load_input_mesh(path, true, true).mesh;  // as `meshsal simplify`
        } catch (const std::bad_alloc&) {
          m.attributed = {};
          m.attributed_error = path + ": out of memory while reading";
        } catch (const std::exception& e) {
          m.attributed_error = e.what();
        }
      }
    } catch (const std::bad_alloc&) {
      m.mesh = {};
      m.error = path + ": out of memory while reading";
    } catch (const std::exception& e) {
      m.error = e.what();
    }
    m.seconds = t.seconds();
    std::unique_lock<std::mutex> l(mutex_);
    if (stop_) return;
    ready_ = std::move(m);
    changed_.notify_all();
  }
}

LoadedModel ModelLoader::next() {
  std::unique_lock<std::mutex> l(mutex_);
  changed_.wait(l, [this] { return ready_.has_value(); });
  LoadedModel m = std::move(*ready_);
  ready_.reset();
  changed_.notify_all();
  return m;
}

}  // namespace meshsal::cli
