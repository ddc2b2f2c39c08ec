// meshsal CLI: the checks on what a command writes. The check of output files is the
// library's (meshsal::check_outputs, meshsal.h), shared with Python and the library's own
// file-to-file calls; the folder a command fills is the command's.
#pragma once
#include <string>
#include <vector>

#include "meshsal/meshsal.h"

namespace meshsal::cli {

using meshsal::check_outputs;
using meshsal::OutputFile;

// For a folder the command fills (demo -o DIR): creates it if missing and checks that it
// is writable. Throws Error.
void prepare_output_folder(const std::string& dir);

}  // namespace meshsal::cli
