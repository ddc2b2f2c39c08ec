#include "json_string.h"

#include <cstdio>

#include "core/utf8.h"

namespace meshsal::cli {
namespace {

std::string hex_escape(const char* form, unsigned value) {
  char buf[16];
  std::snprintf(buf, sizeof buf, form, value);
  return buf;
}

}  // namespace

std::string json_string(const std::string& text) {
  std::string out = "\"";
  for (size_t i = 0; i < text.size();) {
    unsigned code = 0;
    const size_t n = meshsal::utf8_at(text, i, &code);
    if (n == 0) {  // a byte of another encoding
      out += hex_escape("\\udc%02x", static_cast<unsigned char>(text[i]));
      i += 1;
      continue;
    }
    if (code == '"' || code == '\\') out += '\\';
    if (meshsal::control_code(code) || meshsal::bidi_control(code))
      out += hex_escape("\\u%04x", code);
    else
      out.append(text, i, n);
    i += n;
  }
  return out + "\"";
}

std::string printable(const std::string& text) { return meshsal::visible_text(text); }

}  // namespace meshsal::cli
