// meshsal batch under MPI (README, "Across machines: MPI"): how the models are shared over
// the ranks and how what each rank computed reaches rank 0, which alone writes the log, the
// summary and the contact sheet. The models to compute go round by round: in round r, rank k
// computes the (r * ranks + k)-th of them, then every rank's results of the round go to rank
// 0 (mpi_all_gather), which logs them in model order. So the log is one single-process log,
// written as rounds end, and each model is computed by exactly one rank; a rank that is
// interrupted stops the others after the round. With one process a round is one model.
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace meshsal::cli {

// What a rank made of one model, for rank 0 to log.
struct ModelResult {
  uint64_t index = 0;             // the model's place among the inputs
  std::string status;             // "done", "failed" or "interrupted"
  std::string line;               // the log line ("done" and "interrupted")
  std::string error;              // "failed": the message
  std::vector<std::string> notes; // the notices printed while it ran
  bool has_view = false;          // its best-view picture was written
  double seconds = 0;             // reading and computing (the progress estimate)
  int rank = 0;                   // who computed it
};

// How many rounds `models` to compute take on `ranks` ranks.
inline size_t batch_rounds(size_t models, int ranks) { return (models + size_t(ranks) - 1) / size_t(ranks); }

// Bytes and back (for mpi_all_gather). unpack throws std::runtime_error on bytes that
// pack did not make.
std::vector<uint8_t> pack_results(const std::vector<ModelResult>& results);
std::vector<ModelResult> unpack_results(const std::vector<uint8_t>& bytes);

// A collective: every rank passes its result of the round (none when it had no model),
// and receives every rank's, in model order, each with its rank.
std::vector<ModelResult> gather_results(const std::vector<ModelResult>& mine);

}  // namespace meshsal::cli
