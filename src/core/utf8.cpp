// meshsal (internal): UTF-8 decoding and the visible form of text (utf8.h).
#include "core/utf8.h"

#include <cstdio>

namespace meshsal {

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

bool valid_utf8(const std::string& s) {
  unsigned code = 0;
  for (size_t i = 0, n; i < s.size(); i += n)
    if ((n = utf8_at(s, i, &code)) == 0) return false;
  return true;
}

std::string visible_text(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  char buf[16];
  for (size_t i = 0; i < text.size();) {
    unsigned code = 0;
    const size_t n = utf8_at(text, i, &code);
    if (n == 0 || control_code(code)) {
      // A C1 control is two bytes in UTF-8: each is shown.
      for (size_t k = 0; k < (n ? n : 1); ++k) {
        std::snprintf(buf, sizeof buf, "\\x%02x", static_cast<unsigned char>(text[i + k]));
        out += buf;
      }
      i += n ? n : 1;
    } else if (bidi_control(code)) {
      std::snprintf(buf, sizeof buf, "\\u%04x", code);
      out += buf;
      i += n;
    } else {
      out.append(text, i, n);
      i += n;
    }
  }
  return out;
}

}  // namespace meshsal
