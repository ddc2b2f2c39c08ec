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

// Throws meshsal::Error "PATH: problem" when an output has the wrong extension, its folder
// is missing or not writable, it is a folder, two outputs are the same file, or it is the
// same file as one of `inputs` (same device and inode, so through symlinks and hard links
// too: the atomic rename would replace the input). Inputs that do not exist are skipped
// (loading them fails later with its own message).
void check_outputs(const std::vector<OutputFile>& outputs, const std::vector<std::string>& inputs);

// For a folder the command fills (demo -o DIR): creates it if missing and checks that it
// is writable. Throws Error.
void prepare_output_folder(const std::string& dir);

}  // namespace meshsal_cli
