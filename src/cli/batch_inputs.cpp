// meshsal batch: expand_batch_inputs (see batch_inputs.h).
#include "batch_inputs.h"

#include <glob.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <set>

#include "meshsal/meshsal.h"
#include "load_input.h"

namespace meshsal_cli {
namespace {

namespace fs = std::filesystem;
using meshsal::Error;

bool is_glob(const std::string& item) { return item.find_first_of("*?[") != std::string::npos; }

std::vector<std::string> folder_meshes(const std::string& dir) {
  std::vector<std::string> found;
  std::error_code ec;
  fs::directory_iterator it(dir, ec), end;
  if (ec) throw Error(dir + ": cannot list the folder: " + ec.message());
  for (; it != end; it.increment(ec)) {
    if (ec) throw Error(dir + ": cannot list the folder: " + ec.message());
    const fs::path& p = it->path();
    std::error_code ec2;
    if (is_mesh_file_name(p.filename().string()) && !fs::is_directory(p, ec2)) found.push_back(p.string());
  }
  std::sort(found.begin(), found.end());
  return found;
}

std::vector<std::string> glob_matches(const std::string& pattern) {
  glob_t g{};
  const int rc = ::glob(pattern.c_str(), 0, nullptr, &g);
  std::vector<std::string> found;
  if (rc == 0)
    for (size_t i = 0; i < g.gl_pathc; ++i) found.push_back(g.gl_pathv[i]);  // glob sorts them
  ::globfree(&g);
  if (rc == GLOB_NOMATCH || (rc == 0 && found.empty())) throw Error(pattern + ": no file matches");
  if (rc != 0) throw Error(pattern + ": cannot expand the pattern");
  return found;
}

class Expander {
 public:
  std::vector<std::string> out;

  void item(const std::string& it, bool in_list) {
    if (it.size() > 1 && it[0] == '@') {
      if (in_list) throw Error(it + ": a list file inside a list file is not read");
      list(it.substr(1));
      return;
    }
    std::error_code ec;
    if (!is_glob(it) && fs::is_directory(it, ec)) {
      for (const std::string& f : folder_meshes(it)) add(f);
    } else if (is_glob(it) && !fs::exists(it, ec)) {
      for (const std::string& f : glob_matches(it))
        if (fs::is_directory(f, ec)) {
          for (const std::string& g : folder_meshes(f)) add(g);
        } else {
          add(f);
        }
    } else {
      add(it);
    }
  }

  void list(const std::string& path) {
    std::ifstream in(path);
    if (!in) throw Error(path + ": cannot read the list file");
    const fs::path base = fs::path(path).parent_path();
    std::string line;
    while (std::getline(in, line)) {
      while (!line.empty() && (line.back() == '\r' || std::isspace(static_cast<unsigned char>(line.back()))))
        line.pop_back();
      size_t start = 0;
      while (start < line.size() && std::isspace(static_cast<unsigned char>(line[start]))) ++start;
      line = line.substr(start);
      if (line.empty() || line[0] == '#') continue;
      const fs::path p(line);
      item(p.is_absolute() || base.empty() ? line : (base / p).string(), true);
    }
    if (in.bad()) throw Error(path + ": cannot read the list file");
  }

 private:
  std::set<std::string> seen_;

  void add(const std::string& path) {
    std::error_code ec;
    fs::path key = fs::weakly_canonical(path, ec);
    if (ec) key = fs::path(path).lexically_normal();
    if (seen_.insert(key.string()).second) out.push_back(path);
  }
};

}  // namespace

bool is_mesh_file_name(const std::string& path) {
  const std::string ext = mesh_extension(path);
  return ext == ".obj" || ext == ".ply" || ext == ".off" || ext == ".stl";
}

std::vector<std::string> expand_batch_inputs(const std::vector<std::string>& items,
                                             const std::string& list_file) {
  Expander e;
  for (const std::string& it : items) e.item(it, false);
  if (!list_file.empty()) e.list(list_file);
  if (e.out.empty()) throw Error("batch: no mesh file found in the inputs given");
  return e.out;
}

}  // namespace meshsal_cli
