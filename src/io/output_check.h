// meshsal: the check every front end makes on the files it will write (check_outputs,
// declared in meshsal.h), and its helpers for the library's own file-to-file calls.
#pragma once
#include <string>

#include "meshsal/meshsal.h"

namespace meshsal {

// The output check of a library call that writes one binary PLY from one input file
// (saliency_file, simplify_file): Error "OUTPUT: CALL writes a binary PLY: ..." unless
// `output` ends in .ply (a .obj or .glb name would get PLY bytes), then check_outputs
// against `input`, so that the call never replaces its input (through a link either).
void check_ply_output(const std::string& call, const std::string& output, const std::string& input);

// Removes FILE.tmp.XXXXXX files beside `file` that no live writer holds.
void remove_stale_temporaries_of(const std::string& file);

}  // namespace meshsal
