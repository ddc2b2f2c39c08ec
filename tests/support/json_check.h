// JSON checks for the tests (the project has no JSON library): json_valid() is the CLI's
// parser (cli/json_valid.h: one value, RFC 8259 grammar, no extensions); json_number() reads a
// number after "KEY": (the first occurrence), for asserting values.
#pragma once
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <string>

#include "cli/json_valid.h"

namespace meshsal_test {


inline bool json_valid(const std::string& text) { return meshsal::cli::is_json(text); }

// The number after the first "KEY": in `text`; NaN when absent.
inline double json_number(const std::string& text, const std::string& key) {
  const std::string k = "\"" + key + "\": ";
  const size_t at = text.find(k);
  if (at == std::string::npos) return std::nan("");
  return std::strtod(text.c_str() + at + k.size(), nullptr);
}

}  // namespace meshsal_test
