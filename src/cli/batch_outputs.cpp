// meshsal batch: output names (see batch_outputs.h).
#include "batch_outputs.h"

#include <sys/stat.h>

#include <algorithm>
#include <cctype>
#include <map>
#include <set>

#include "batch_state.h"

namespace meshsal::cli {
std::string file_name(const std::string& path) {
  const size_t slash = path.find_last_of('/');
  return slash == std::string::npos ? path : path.substr(slash + 1);
}

namespace {

// "bunny.ply.gz" -> "bunny"; a name without a mesh extension stays whole.
std::string stem(const std::string& name) {
  std::string lower = name;
  for (char& c : lower) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  size_t end = name.size();
  if (lower.size() > 3 && lower.compare(lower.size() - 3, 3, ".gz") == 0) end -= 3;
  for (const std::string ext : {".obj", ".ply", ".off", ".stl", ".glb", ".gltf"})
    if (end > ext.size() && lower.compare(end - ext.size(), ext.size(), ext) == 0) return name.substr(0, end - ext.size());
  return name;
}

}  // namespace

std::vector<std::string> ModelOutputs::all() const {
  std::vector<std::string> v{saliency};
  if (!view.empty()) v.push_back(view);
  if (!simplified.empty()) v.push_back(simplified);
  if (!page.empty()) v.push_back(page);
  if (!lod.empty()) v.push_back(lod);
  return v;
}

std::vector<std::string> output_names(const std::vector<std::string>& inputs) {
  std::map<std::string, int> stems;
  for (const std::string& in : inputs) stems[stem(file_name(in))]++;
  std::vector<std::string> names;
  std::map<std::string, int> used;
  std::set<std::string> taken;
  for (const std::string& in : inputs) {
    const std::string whole = file_name(in), short_name = stem(whole);
    std::string name = stems[short_name] > 1 ? whole : short_name;
    const int n = ++used[name];
    if (n > 1) name += "_" + std::to_string(n);
    while (!taken.insert(name).second) name += "_";  // a file really named bunny_2.obj
    names.push_back(name);
  }
  return names;
}

ModelOutputs model_outputs(const std::string& dir, const std::string& name, bool view, bool simplified,
                           bool simplified_ply, bool page, bool lod) {
  const std::string base = dir + (dir.empty() || dir.back() == '/' ? "" : "/") + name;
  ModelOutputs o;
  o.saliency = base + "_saliency.ply";
  if (view) o.view = base + "_view.png";
  if (simplified) o.simplified = base + (simplified_ply ? "_simplified.ply" : "_simplified.obj");
  if (page) o.page = base + "_view.html";
  if (lod) o.lod = base + "_lod.glb";
  return o;
}

std::vector<std::string> without_batch_outputs(const std::vector<std::string>& inputs, const std::string& dir) {
  struct stat ds;
  if (::stat(dir.c_str(), &ds) != 0) return inputs;  // no output folder yet: nothing written
  // The inputs that might be outputs: in `dir`, with an output's ending; NAME before it.
  std::vector<std::string> name(inputs.size());
  std::vector<size_t> maybe;
  for (size_t i = 0; i < inputs.size(); ++i) {
    const std::string file = file_name(inputs[i]);
    for (const char* end : {"_saliency.ply", "_simplified.obj", "_simplified.ply", "_lod.glb"}) {
      const std::string e(end);
      if (file.size() <= e.size() || file.compare(file.size() - e.size(), e.size(), e) != 0) continue;
      const size_t slash = inputs[i].find_last_of('/');
      const std::string folder = slash == std::string::npos ? "." : slash == 0 ? "/" : inputs[i].substr(0, slash);
      struct stat fs;
      if (::stat(folder.c_str(), &fs) == 0 && fs.st_dev == ds.st_dev && fs.st_ino == ds.st_ino) {
        name[i] = file.substr(0, file.size() - e.size());
        maybe.push_back(i);
      }
    }
  }
  if (maybe.empty()) return inputs;
  std::vector<bool> keep(inputs.size(), true);
  for (size_t i : maybe) keep[i] = false;
  // Shortest names first: a user's own x_saliency.ply kept is the model whose outputs
  // x_saliency_saliency.ply are.
  std::stable_sort(maybe.begin(), maybe.end(),
                   [&](size_t a, size_t b) { return file_name(inputs[a]).size() < file_name(inputs[b]).size(); });
  const auto kept_names = [&] {
    std::vector<std::string> kept;
    for (size_t i = 0; i < inputs.size(); ++i)
      if (keep[i]) kept.push_back(inputs[i]);
    const std::vector<std::string> names = output_names(kept);
    return std::set<std::string>(names.begin(), names.end());
  };
  std::set<std::string> names = kept_names();
  for (size_t i : maybe) {
    struct stat ss;
    if (names.count(name[i]) && ::stat(state_path(dir, name[i]).c_str(), &ss) == 0) continue;  // an output
    keep[i] = true;
    names = kept_names();
  }
  std::vector<std::string> out;
  for (size_t i = 0; i < inputs.size(); ++i)
    if (keep[i]) out.push_back(inputs[i]);
  return out;
}

}  // namespace meshsal::cli
