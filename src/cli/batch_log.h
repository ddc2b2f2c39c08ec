// meshsal batch: the JSON Lines log, one object per model (json_object.h's conventions),
// appended line by line as models finish: what a run did is on disk even when it is
// killed, and a later run's lines follow the earlier ones'. A line that cannot be written
// (a full disk) is reported once on stderr and the run goes on; failed() tells the end.
#pragma once
#include <memory>
#include <string>

#include "io/append_file.h"

namespace meshsal_cli {

class BatchLog {
 public:
  // Opens (creates) the log for appending. Throws meshsal::Error naming it.
  explicit BatchLog(const std::string& path) : file_(std::make_unique<meshsal::AppendFile>(path)) {}
  void add(const std::string& json_line);  // never throws for a failed write
  void finish();                           // syncs it to disk (a failure counts as failed())
  size_t lost() const { return lost_; }    // lines that could not be written
  const std::string& error() const { return error_; }  // the first write error
  const std::string& path() const { return file_->path(); }

 private:
  void failed(const std::string& error);
  std::unique_ptr<meshsal::AppendFile> file_;
  size_t lost_ = 0;
  std::string error_;
};

}  // namespace meshsal_cli
