// meshsal batch: the JSON Lines log, one object per model (json_object.h's conventions),
// appended line by line as models finish: what a run did is on disk even when it is
// killed, and a later run's lines follow the earlier ones'. A line that cannot be written
// (a full disk) is reported once on stderr and the run goes on; failed() tells the end.
#pragma once
#include <cstdint>
#include <memory>
#include <string>

#include "io/append_file.h"

namespace meshsal::cli {

// The bytes of the last line of the regular file at `path` when that line is torn: not one
// JSON value (a run killed part way through writing it; a last line cut short before its
// newline is one). 0 when the file ends with a whole JSON line (a valid line missing only
// its newline counts as whole), is empty, missing, or not a regular file. Blank lines at the
// end are passed over.
uint64_t torn_last_line(const std::string& path);

class BatchLog {
 public:
  // Opens (creates) the log for appending; a last line without its newline gets one first,
  // so the new lines start on a line of their own (torn_bytes() tells whether that line was
  // torn). Throws meshsal::Error naming it.
  explicit BatchLog(const std::string& path)
      : torn_(torn_last_line(path)), file_(std::make_unique<meshsal::AppendFile>(path)) {}
  void add(const std::string& json_line);  // never throws for a failed write
  void finish();                           // syncs it to disk (a failure counts as failed())
  size_t lost() const { return lost_; }    // lines that could not be written
  const std::string& error() const { return error_; }  // the first write error
  const std::string& path() const { return file_->path(); }
  // The bytes of the torn last line an interrupted run left (0: none); readers skip it.
  uint64_t torn_bytes() const { return torn_; }

 private:
  void failed(const std::string& error);
  uint64_t torn_;
  std::unique_ptr<meshsal::AppendFile> file_;
  size_t lost_ = 0;
  std::string error_;
};

}  // namespace meshsal::cli
