// meshsal batch: BatchLog (see batch_log.h).
#include "batch_log.h"

#include <cstdio>

#include "json_string.h"
#include "meshsal/meshsal.h"

namespace meshsal_cli {

void BatchLog::add(const std::string& json_line) {
  try {
    file_->append(json_line);
  } catch (const meshsal::Error& e) {
    ++lost_;
    failed(std::string(e.what()) + ": the log misses this model's line; the run goes on");
  }
}

void BatchLog::finish() {
  try {
    file_->sync();
  } catch (const meshsal::Error& e) {
    failed(e.what());
  }
}

void BatchLog::failed(const std::string& error) {
  if (!error_.empty()) return;  // once: the same reason would follow every model
  error_ = error;
  std::fprintf(stderr, "error: %s\n", printable(error).c_str());
}

}  // namespace meshsal_cli
