// meshsal CLI: the checks every command makes on the files it will write, before any work
// (loading, saliency, rendering), so that a typo costs nothing and an input is never lost.
#pragma once
#include <string>
#include <vector>

namespace meshsal_cli {

struct OutputFile {
  std::string path;                     // as given; "" = not requested (skipped)
  std::string option;                   // e.g. "-o" or "--map", for the messages
  std::vector<std::string> extensions;  // accepted endings, lower case (".png"); empty = any
};

// Throws meshsal::Error "PATH: problem" when an output has the wrong extension, cannot be
// written by the writers' rule (meshsal::output_target: a folder, a disk, a socket, a
// missing or unwritable folder), two outputs are the same file, or it is the same file as
// one of `inputs` (same device and inode, so through symlinks and hard links too: the
// atomic rename would replace the input). Inputs that do not exist are skipped (loading
// them fails later with its own message). Then removes the temporaries that an earlier
// run killed while writing these outputs left behind (remove_stale_temporaries_of).
void check_outputs(const std::vector<OutputFile>& outputs, const std::vector<std::string>& inputs);

// Removes FILE.tmp.XXXXXX files beside `file` that no live writer holds.
void remove_stale_temporaries_of(const std::string& file);

// For a folder the command fills (demo -o DIR): creates it if missing and checks that it
// is writable. Throws Error.
void prepare_output_folder(const std::string& dir);

}  // namespace meshsal_cli
