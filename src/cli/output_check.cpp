#include "output_check.h"

#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>

namespace meshsal::cli {

using meshsal::Error;

void prepare_output_folder(const std::string& dir) {
  if (dir.empty()) throw Error("the output folder name is empty");
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) throw Error(dir + ": cannot create the output folder: " + ec.message());
  if (::access(dir.c_str(), W_OK | X_OK) != 0)
    throw Error(dir + ": cannot write: folder '" + dir + "' is not writable (" + std::strerror(errno) + ")");
}

}  // namespace meshsal::cli
