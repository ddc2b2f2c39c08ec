// meshsal: files that a model names (a glTF buffer or image URI, an OBJ's mtllib): the one
// rule for where they may lie, and the one way they are read.
//
// A model comes from a stranger as often as not, and a name inside it must not make
// meshsal read (and copy into an output) any file the user did not point at: a glTF
// image URI of ../../../../proc/self/environ put the process environment into the output.
// So a reference is a relative path, '/'-separated, that stays in the model's folder or
// below: no absolute path, no '..' that leaves the folder, no symbolic link on the way that
// leads out of it, no URI scheme (glTF's data: URIs are decoded by the glTF reader and never
// get here). A refusal names the reference and the rule and says nothing about the file the
// reference would reach (not even whether it exists).
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "meshsal/meshsal.h"

namespace meshsal {

// The rule in the words every refusal uses.
constexpr const char* kReferenceRule = "a model may name only files in its own folder or below";

// A reference refused by the rule (not merely missing or unreadable): a model that names
// its way out of its folder is refused whole, whatever names it.
struct ReferenceRefused : Error {
  using Error::Error;
};

// Why the reference cannot name a file in the model's folder by its text alone ("" when it
// can): empty, a NUL byte, absolute, a URI scheme ("http:", "file:"; when `uri`), or more
// '..' than folders before them. `uri`: the reference is a URI (glTF), already
// percent-decoded, so "scheme:" at its start is a scheme; an OBJ's names are plain paths.
std::string reference_text_problem(const std::string& reference, bool uri);

// The bytes of the file `reference` names in the model's folder `folder` ("." or a path,
// with or without a trailing '/'), under the rule above, symbolic links resolved: a regular
// file (no FIFO, device or folder), at most `budget` bytes. Throws ReferenceRefused
// "'REFERENCE': ..." when the rule refuses it, Error when it is missing or cannot be read
// (the caller prefixes the model's name).
std::vector<unsigned char> read_model_reference(const std::string& folder, const std::string& reference, bool uri,
                                                uint64_t budget);

}  // namespace meshsal
