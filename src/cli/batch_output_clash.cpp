// meshsal batch: the run's outputs apart from each other and from the models' (batch_output_clash.h).
#include "batch_output_clash.h"

#include <sys/stat.h>

#include <filesystem>
#include <map>

#include "batch_state.h"
#include "command.h"
#include "io/atomic_write.h"
#include "meshsal/meshsal.h"

namespace meshsal::cli {
namespace {

namespace fs = std::filesystem;

// Where writing a path puts its file: the folder (its device and inode; its path where it
// does not exist yet) and the name in it, and the file's own identity where it exists.
struct Place {
  std::string folder, name;
  bool exists = false;
  dev_t dev = 0;
  ino_t ino = 0;
  bool same_file(const Place& o) const {
    return (folder == o.folder && name == o.name) || (exists && o.exists && dev == o.dev && ino == o.ino);
  }
};

class Places {
 public:
  Place of(const std::string& path) {
    std::string target = path;
    struct stat ls;
    if (::lstat(path.c_str(), &ls) == 0 && S_ISLNK(ls.st_mode)) {
      try {
        target = meshsal::output_target(path).path;  // the file the link names: the one written
      } catch (const meshsal::Error&) {
        // a link to a folder or a device: check_outputs tells what is wrong with it
      }
    }
    const fs::path p(target);
    Place place;
    place.folder = folder_key(p.has_parent_path() ? p.parent_path().string() : ".");
    place.name = p.filename().string();
    struct stat st;
    if (::stat(target.c_str(), &st) == 0) place.exists = true, place.dev = st.st_dev, place.ino = st.st_ino;
    return place;
  }

 private:
  std::map<std::string, std::string> folders_;  // one stat per folder (every model's is DIR)
  const std::string& folder_key(const std::string& folder) {
    auto it = folders_.find(folder);
    if (it != folders_.end()) return it->second;
    struct stat st;
    std::string key;
    if (::stat(folder.c_str(), &st) == 0) {
      key = std::to_string(st.st_dev) + ":" + std::to_string(st.st_ino);
    } else {
      std::error_code ec;
      key = "path:" + fs::weakly_canonical(fs::absolute(folder, ec), ec).string();
    }
    return folders_.emplace(folder, key).first->second;
  }
};

[[noreturn]] void clash(const RunOutput& a, const std::string& b) {
  throw UsageError(a.path + ": given for both " + a.what + " and " + b +
                   " (every file a batch writes is a file of its own)");
}

}  // namespace

void check_batch_outputs_apart(const std::string& dir, const std::vector<RunOutput>& run,
                               const std::vector<std::string>& inputs, const std::vector<std::string>& names,
                               const std::vector<ModelOutputs>& outs) {
  Places places;
  std::vector<RunOutput> given;
  std::vector<Place> at;
  for (const RunOutput& r : run) {
    if (r.path.empty()) continue;
    const Place p = places.of(r.path);
    for (size_t k = 0; k < given.size(); ++k)
      if (at[k].same_file(p)) clash(given[k], r.what);
    given.push_back(r);
    at.push_back(p);
  }
  if (given.empty()) return;
  const auto check = [&](const std::string& path, const std::string& what, const std::string& input) {
    const Place p = places.of(path);
    for (size_t k = 0; k < given.size(); ++k)
      if (at[k].same_file(p)) clash(given[k], what + (input.empty() ? "" : " of " + input));
  };
  const std::string records = fs::path(state_path(dir, "x")).parent_path().string();
  check(records, "the folder of the resume records", "");
  for (size_t i = 0; i < outs.size(); ++i) {
    const ModelOutputs& o = outs[i];
    check(o.saliency, "the saliency output", inputs[i]);
    if (!o.view.empty()) check(o.view, "the best-view picture", inputs[i]);
    if (!o.simplified.empty()) check(o.simplified, "the simplified mesh", inputs[i]);
    if (!o.page.empty()) check(o.page, "the page", inputs[i]);
    if (!o.lod.empty()) check(o.lod, "the levels of detail", inputs[i]);
    check(state_path(dir, names[i]), "the resume record", inputs[i]);
  }
}

}  // namespace meshsal::cli
