// meshsal: how deeply a JSON text nests, found without recursion, so that a file can be
// refused before any parser recurses into it. A 40 KB glTF whose `extras` nested 20,000
// arrays overflowed the stack of tinygltf's JSON-to-value conversion (SIGSEGV in every
// front end, the Python interpreter included).
#pragma once
#include <cstddef>
#include <string_view>

namespace meshsal {

// The deepest nesting of arrays and objects meshsal reads from a file (glTF, a GLB's JSON
// chunk). Real files stay far below it: a glTF's own structure nests 6 deep, and the
// extras and extensions of common exporters a few more.
constexpr size_t kMaxJsonNesting = 64;

// The deepest nesting of [ and { in `text` (0 for a scalar), strings skipped with their
// escapes; the count stops at `stop_after` + 1 (so a huge file is not scanned to its end
// once it is known to be too deep). Not a validator: malformed text is the parser's
// business, and brackets are only counted, not matched.
size_t json_nesting(std::string_view text, size_t stop_after = kMaxJsonNesting);

}  // namespace meshsal
