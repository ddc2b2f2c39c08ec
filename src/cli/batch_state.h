// meshsal batch: what each model's outputs were made from, so that a run resumes where
// the last one stopped and recomputes whatever changed. A model is up to date when its
// record in DIR/.meshsal-batch/NAME.state says its outputs were made from this input (same
// size, modification time and content hash) with these options, and every output is
// still there with the size it was written with.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

namespace meshsal::cli {

// An input file as it is now.
struct InputFingerprint {
  uint64_t size = 0;
  int64_t mtime_ns = 0;
  uint64_t hash = 0;  // FNV-1a of the whole file up to 1 MiB, else of its first and last
                      // 64 KiB and 64 samples of 4 KiB spread over the rest
  bool operator==(const InputFingerprint& o) const {
    return size == o.size && mtime_ns == o.mtime_ns && hash == o.hash;
  }
};

// Throws meshsal::Error when the file cannot be read.
InputFingerprint fingerprint(const std::string& path);

struct ModelState {
  InputFingerprint input;
  std::string options;                   // the options that shape the outputs, as one line
  std::vector<uint64_t> output_sizes;    // bytes, one per output (ModelOutputs::all() order)
  std::string record;                    // the log line of the run that made them
};

// DIR/.meshsal-batch/NAME.state
std::string state_path(const std::string& dir, const std::string& name);

// Writes the record atomically (the folder is made if missing). Throws Error.
void save_state(const std::string& path, const ModelState& state);

// Writes a record that names no outputs yet (load_state: false) where there is none: a
// batch is making this model's outputs (batch_outputs.h: without_batch_outputs then
// knows them for outputs, should the run stop before save_state). Throws Error.
void mark_started(const std::string& path);

// The record at `path`; false when there is none or it is not one save_state wrote: not a
// regular file (a link, a FIFO, a device), larger than 1 MiB, torn (no last newline), or
// any line out of save_state's form (whole numbers in full, the record valid_record). The caller computes the model again; nothing of a bad file
// reaches the log.
bool load_state(const std::string& path, ModelState* state);

// True when `record` can be a skipped model's log line: one JSON object (json_valid.h),
// valid UTF-8 without control characters (one line), with its "status": "done" member.
bool valid_record(const std::string& record);

// True when `saved` describes outputs made from `input` with `options`, and each of
// `outputs` exists as a regular file of its recorded size.
bool up_to_date(const ModelState& saved, const InputFingerprint& input, const std::string& options,
                const std::vector<std::string>& outputs);

}  // namespace meshsal::cli
