#include "output_check.h"

#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>

namespace meshsal_cli {

using meshsal::Error;

void prepare_output_folder(const std::string& dir) {
  if (dir.empty()) throw Error("the output folder name is empty");
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) throw Error(dir + ": cannot create the output folder: " + ec.message());
  if (::access(dir.c_str(), W_OK | X_OK) != 0)
    throw Error(dir + ": cannot write: folder '" + dir + "' is not writable (" + std::strerror(errno) + ")");
}

std::string material_files_note(const std::string& input, const std::string& output,
                                const std::vector<std::string>& material_libraries) {
  namespace fs = std::filesystem;
  std::string relative;
  for (const std::string& lib : material_libraries)
    if (!fs::path(lib).is_absolute()) relative += (relative.empty() ? "" : " ") + lib;
  if (relative.empty() || input == "-") return "";
  std::error_code ec;
  const auto folder = [&](const std::string& file) {
    return fs::weakly_canonical(fs::absolute(fs::path(file), ec).parent_path(), ec);
  };
  if (folder(input) == folder(output)) return "";
  return "note: " + output + " names the material file(s) " + relative + " as " + input +
         " does, relative to its folder: copy them (and their textures) beside it";
}

}  // namespace meshsal_cli
