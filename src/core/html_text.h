// meshsal (internal): text put into HTML (the viewer page, batch's gallery).
#pragma once
#include <string>

#include "core/utf8.h"

namespace meshsal {

// `s` safe in element text and in double-quoted attributes (& < > " as entities), and shown
// as its bytes are (visible_text): a file name's bytes that are not UTF-8, its control
// characters and its bidirectional controls appear as \xXX and \uXXXX escapes, so a name
// can neither break the page's encoding nor show its letters in another order.
inline std::string html_escaped(const std::string& s) {
  std::string out;
  for (char c : visible_text(s)) {
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
