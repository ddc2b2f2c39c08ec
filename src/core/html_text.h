// meshsal (internal): text put into HTML (the viewer page, batch's gallery).
#pragma once
#include <string>

namespace meshsal {

// `s` with & < > " as entities: safe in element text and in double-quoted attributes.
inline std::string html_escaped(const std::string& s) {
  std::string out;
  for (char c : s) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      default: out += c;
    }
  }
  return out;
}

}  // namespace meshsal
