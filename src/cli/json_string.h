// meshsal CLI: text that leaves the program safely: JSON string literals (every --json
// output and the batch log) and lines for a terminal (messages naming files).
#pragma once
#include <string>

namespace meshsal::cli {

// `text` as a JSON string literal, quotes included, valid JSON and valid UTF-8 whatever
// the bytes: quotes and backslashes escaped, control characters (C0, DEL and C1) as
// \u00XX, bidirectional controls (core/utf8.h: they reorder what a viewer shows) as \uXXXX,
// and each byte that is not part of valid UTF-8 (a file name in another encoding) as the
// lone surrogate \udcXX (XX the byte, 80..ff), the escape Python's surrogateescape uses:
// json.loads(...) then os.fsencode(...) gives the original bytes.
std::string json_string(const std::string& text);

// `text` fit to print on a terminal as one line: control characters (C0 including
// newline and ESC, DEL, C1) and bytes that are not valid UTF-8 become \xXX, bidirectional
// controls \uXXXX (meshsal::visible_text), so a file name can neither split a message, send
// escape sequences to the terminal nor reorder what the line shows.
std::string printable(const std::string& text);

}  // namespace meshsal::cli
