// meshsal batch: no two of the files a run writes are one file. The log, the contact sheet
// and the gallery are named by the user, so one of them can be a model's output (--log
// results/ball_saliency.ply): each writer would replace the other's file and the run would
// still end with status 0. Checked before any work.
#pragma once
#include <string>
#include <vector>

#include "batch_outputs.h"

namespace meshsal::cli {

struct RunOutput {
  std::string path;  // "" = not written by this run
  std::string what;  // for the message: "--log", "--contact-sheet", "--html's gallery"
};

// Throws UsageError "PATH: given for both A and B (...)" when two of `run` are one file, or
// one of them is a model's output (`outs[i]` of `inputs[i]`), its resume record
// (batch_state.h: state_path(dir, names[i])) or the records' folder. One file means the same
// folder (by device and inode) and name, with links followed as the writers follow them
// (meshsal::output_target), or, for files that exist, the same device and inode (a hard
// link). The models' own files never share a name (output_names), so they are compared
// with the run's only: a few comparisons per model.
void check_batch_outputs_apart(const std::string& dir, const std::vector<RunOutput>& run,
                               const std::vector<std::string>& inputs, const std::vector<std::string>& names,
                               const std::vector<ModelOutputs>& outs);

}  // namespace meshsal::cli
