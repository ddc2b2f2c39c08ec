#include "json_string.h"

#include <cstdio>

namespace meshsal_cli {
namespace {

// The length of the valid UTF-8 sequence starting at s[i] (shortest form, no surrogates,
// at most U+10FFFF), 0 when the byte there starts none; *code receives the code point.
size_t utf8_at(const std::string& s, size_t i, unsigned* code) {
  const unsigned char c = static_cast<unsigned char>(s[i]);
  if (c < 0x80) return *code = c, 1;
  size_t n;
  unsigned cp, min;
  if (c >= 0xc2 && c <= 0xdf) n = 2, cp = c & 0x1f, min = 0x80;
  else if (c >= 0xe0 && c <= 0xef) n = 3, cp = c & 0x0f, min = 0x800;
  else if (c >= 0xf0 && c <= 0xf4) n = 4, cp = c & 0x07, min = 0x10000;
  else return 0;
  if (i + n > s.size()) return 0;
  for (size_t k = 1; k < n; ++k) {
    const unsigned char d = static_cast<unsigned char>(s[i + k]);
    if ((d & 0xc0) != 0x80) return 0;
    cp = (cp << 6) | (d & 0x3f);
  }
  if (cp < min || cp > 0x10ffff || (cp >= 0xd800 && cp <= 0xdfff)) return 0;
  *code = cp;
  return n;
}

bool control(unsigned code) { return code < 0x20 || (code >= 0x7f && code <= 0x9f); }

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
    const size_t n = utf8_at(text, i, &code);
    if (n == 0) {  // a byte of another encoding
      out += hex_escape("\\udc%02x", static_cast<unsigned char>(text[i]));
      i += 1;
      continue;
    }
    if (code == '"' || code == '\\') out += '\\';
    if (control(code))
      out += hex_escape("\\u%04x", code);
    else
      out.append(text, i, n);
    i += n;
  }
  return out + "\"";
}

std::string printable(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  for (size_t i = 0; i < text.size();) {
    unsigned code = 0;
    const size_t n = utf8_at(text, i, &code);
    if (n == 0 || control(code)) {
      // A C1 control is two bytes in UTF-8: each is shown.
      for (size_t k = 0; k < (n ? n : 1); ++k) out += hex_escape("\\x%02x", static_cast<unsigned char>(text[i + k]));
      i += n ? n : 1;
      continue;
    }
    out.append(text, i, n);
    i += n;
  }
  return out;
}

}  // namespace meshsal_cli
