// meshsal batch: the JSON Lines log, one object per model (json_object.h's conventions).
// It is rewritten atomically (write_file_atomically) at most every 2 seconds while the
// run goes on and once at its end, so it is never half a file and a long run can be
// watched.
#pragma once
#include <chrono>
#include <string>
#include <vector>

namespace meshsal_cli {

class BatchLog {
 public:
  explicit BatchLog(std::string path) : path_(std::move(path)) {}
  void add(const std::string& json_line);  // may write the file
  void finish();                           // writes the file (throws Error naming it)
  const std::string& path() const { return path_; }

 private:
  void write();
  std::string path_;
  std::vector<std::string> lines_;
  std::chrono::steady_clock::time_point last_write_ = std::chrono::steady_clock::now();
};

}  // namespace meshsal_cli
