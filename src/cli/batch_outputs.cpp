// meshsal batch: output names (see batch_outputs.h).
#include "batch_outputs.h"

#include <cctype>
#include <map>
#include <set>

namespace meshsal_cli {
namespace {

std::string file_name(const std::string& path) {
  const size_t slash = path.find_last_of('/');
  return slash == std::string::npos ? path : path.substr(slash + 1);
}

// "bunny.ply.gz" -> "bunny"; a name without a mesh extension stays whole.
std::string stem(const std::string& name) {
  std::string lower = name;
  for (char& c : lower) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  size_t end = name.size();
  if (lower.size() > 3 && lower.compare(lower.size() - 3, 3, ".gz") == 0) end -= 3;
  for (const char* ext : {".obj", ".ply", ".off", ".stl"})
    if (end > 4 && lower.compare(end - 4, 4, ext) == 0) return name.substr(0, end - 4);
  return name;
}

}  // namespace

std::vector<std::string> ModelOutputs::all() const {
  std::vector<std::string> v{saliency};
  if (!view.empty()) v.push_back(view);
  if (!simplified.empty()) v.push_back(simplified);
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

ModelOutputs model_outputs(const std::string& dir, const std::string& name, bool view, bool simplified) {
  const std::string base = dir + (dir.empty() || dir.back() == '/' ? "" : "/") + name;
  ModelOutputs o;
  o.saliency = base + "_saliency.ply";
  if (view) o.view = base + "_view.png";
  if (simplified) o.simplified = base + "_simplified.obj";
  return o;
}

}  // namespace meshsal_cli
