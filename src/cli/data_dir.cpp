#include "cli/data_dir.h"

#include <cstdlib>
#include <filesystem>

namespace meshsal {

std::string benchmark_data_dir() {
  const char* env = std::getenv("MESHSAL_DATA");
  if (env && *env) return env;
  namespace fs = std::filesystem;
  if (fs::is_directory("../shared/data/meshes")) return "../shared/data/meshes";
  std::error_code ec;
  fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    fs::path guess = exe.parent_path().parent_path().parent_path() / "shared/data/meshes";
    if (fs::is_directory(guess)) return guess.string();
  }
  return "../shared/data/meshes";
}

}  // namespace meshsal
