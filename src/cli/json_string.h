// meshsal CLI: JSON string literals for the commands that print one JSON object.
#pragma once
#include <string>

namespace meshsal_cli {

// `text` as a JSON string literal, quotes included: quotes, backslashes and control
// characters escaped.
std::string json_string(const std::string& text);

}  // namespace meshsal_cli
