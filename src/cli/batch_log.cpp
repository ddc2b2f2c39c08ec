// meshsal batch: BatchLog (see batch_log.h).
#include "batch_log.h"

#include "io/atomic_write.h"

namespace meshsal_cli {

void BatchLog::add(const std::string& json_line) {
  lines_.push_back(json_line);
  if (std::chrono::steady_clock::now() - last_write_ >= std::chrono::seconds(2)) write();
}

void BatchLog::finish() { write(); }

void BatchLog::write() {
  meshsal::write_file_atomically(path_, [this](std::FILE* f) {
    for (const std::string& line : lines_) {
      meshsal::write_all(f, line.data(), line.size(), path_);
      meshsal::write_all(f, "\n", 1, path_);
    }
  });
  last_write_ = std::chrono::steady_clock::now();
}

}  // namespace meshsal_cli
