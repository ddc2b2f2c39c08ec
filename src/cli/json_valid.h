// meshsal CLI: is a text one JSON value? (the batch log's torn-line check; the tests'
// json_valid() uses the same parser).
#pragma once
#include <string>

namespace meshsal::cli {

// True when `text` is exactly one JSON value (RFC 8259, no extensions; blanks around it
// allowed; nesting deeper than 64 is refused).
bool is_json(const std::string& text);

// True when `text` is one line of a JSON Lines file: is_json, valid UTF-8, and no control
// character (no newline, no CR) anywhere.
bool is_json_line(const std::string& text);

}  // namespace meshsal::cli
