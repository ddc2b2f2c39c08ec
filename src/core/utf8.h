// meshsal (internal): the text of file names and of files, as it leaves the program. One
// UTF-8 decoder and one rule for what is shown escaped, for every place such text goes:
// JSON strings (cli/json_string.h), terminal lines (printable) and HTML (html_text.h).
#pragma once
#include <cstddef>
#include <string>

namespace meshsal {

// The length of the valid UTF-8 sequence starting at s[i] (shortest form, no surrogates,
// at most U+10FFFF), 0 when the byte there starts none; *code receives the code point.
size_t utf8_at(const std::string& s, size_t i, unsigned* code);

// True when all of `s` is valid UTF-8 (utf8_at's rule).
bool valid_utf8(const std::string& s);

// C0 (newline, ESC ...), DEL and C1: they split lines or start terminal escape sequences.
inline bool control_code(unsigned code) { return code < 0x20 || (code >= 0x7f && code <= 0x9f); }

// The bidirectional formatting characters (U+202A..202E embeddings and overrides,
// U+2066..2069 isolates, the marks U+200E, U+200F and U+061C): invisible, yet they
// reorder the text shown around them, so "evil\u202egnp.obj" reads as "evilobj.png".
inline bool bidi_control(unsigned code) {
  return (code >= 0x202a && code <= 0x202e) || (code >= 0x2066 && code <= 0x2069) || code == 0x200e ||
         code == 0x200f || code == 0x061c;
}

// `text` fit to show as one line, reading as its bytes are: each byte that is not valid
// UTF-8 and each byte of a control character as \xXX, a bidirectional control as \uXXXX
// (four lower-case hex digits); everything else, other UTF-8 included, as it is.
std::string visible_text(const std::string& text);

}  // namespace meshsal
