// meshsal: tiny line/token scanner shared by the text parsers (OBJ, OFF, ascii PLY).
// Works on the file bytes in memory; numbers via std::from_chars (no iostreams, no locale).
#pragma once
#include <algorithm>
#include <charconv>
#include <cstring>
#include <cstdlib>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "meshsal/meshsal.h"

namespace meshsal {

struct TextScan {
  std::string_view text;
  const std::string& name;  // the input's name, for errors found while scanning
  size_t pos = 0;
  size_t line_no = 0;  // 1-based number of the line last returned by next_line
  char line_end = 0;   // what ended that line: '\n' (or "\r\n"), '\r' (a lone CR), 0 (end of text)

  TextScan(std::string_view t, const std::string& input_name) : text(t), name(input_name) {}

  bool at_end() const { return pos >= text.size(); }

  // Skips a UTF-8 byte-order mark at the start (editors on Windows write one); true when
  // there was one. UTF-16 text is refused: every byte would be read wrong.
  bool skip_bom() {
    if (text.substr(pos, 2) == "\xFF\xFE" || text.substr(pos, 2) == "\xFE\xFF")
      throw Error(name + ": UTF-16 text (it starts with a UTF-16 byte-order mark); save it as UTF-8 or ASCII");
    if (text.substr(pos, 3) != kBom) return false;
    pos += 3;
    return true;
  }

  // The next line without its line end; false at the end of the text. "\n", "\r\n" and a
  // lone "\r" (classic Mac OS) all end a line: a lone CR must not glue two lines together
  // (an OBJ "v" line would silently swallow the next one as extra columns).
  bool next_line(std::string_view& line) {
    if (pos >= text.size()) return false;
    if (newline_ < pos || newline_ == kUnknown) {
      const void* nl = std::memchr(text.data() + pos, '\n', text.size() - pos);
      newline_ = nl ? static_cast<size_t>(static_cast<const char*>(nl) - text.data()) : text.size();
    }
    size_t end = newline_, next = newline_ + 1;
    line_end = newline_ < text.size() ? '\n' : 0;
    if (const void* cr = std::memchr(text.data() + pos, '\r', newline_ - pos)) {
      end = static_cast<size_t>(static_cast<const char*>(cr) - text.data());
      if (end + 1 != newline_ || newline_ == text.size()) {
        next = end + 1;
        line_end = '\r';
      }
    }
    line = text.substr(pos, end - pos);
    pos = std::min(next, text.size());
    ++line_no;
    if (line.substr(0, 3) == kBom)
      throw Error(name + ": line " + std::to_string(line_no) +
                  ": a UTF-8 byte-order mark inside the file (were two files joined together?)");
    return true;
  }

  static constexpr std::string_view kBom = "\xEF\xBB\xBF";

 private:
  static constexpr size_t kUnknown = ~size_t(0);
  size_t newline_ = kUnknown;  // position of the next '\n' at or after pos (or text.size())
};

inline bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }

// Strips a '#' comment and surrounding blanks.
inline std::string_view strip_comment(std::string_view line) {
  size_t hash = line.find('#');
  if (hash != std::string_view::npos) line = line.substr(0, hash);
  while (!line.empty() && is_space(line.front())) line.remove_prefix(1);
  while (!line.empty() && is_space(line.back())) line.remove_suffix(1);
  return line;
}

// Next blank-separated token of `s` (consumed from it); empty when none is left.
inline std::string_view next_token(std::string_view& s) {
  size_t i = 0;
  while (i < s.size() && is_space(s[i])) ++i;
  size_t j = i;
  while (j < s.size() && !is_space(s[j])) ++j;
  std::string_view tok = s.substr(i, j - i);
  s.remove_prefix(j);
  return tok;
}

// Whole token as a number; false when it is not one (or out of range).
template <typename T>
inline bool parse_number(std::string_view tok, T& out) {
  if (!tok.empty() && tok.front() == '+') tok.remove_prefix(1);
  if (tok.empty()) return false;
  auto r = std::from_chars(tok.data(), tok.data() + tok.size(), out);
  return r.ec == std::errc() && r.ptr == tok.data() + tok.size();
}

// Coordinates: like parse_number, but a value too large or too small for float becomes
// +-inf / a (sub)normal or 0 as strtod would round it, instead of failing; validate_mesh
// then rejects the infinities with a clear message.
template <typename Real>
inline bool parse_coord(std::string_view tok, Real& out) {
  if (!tok.empty() && tok.front() == '+') tok.remove_prefix(1);
  if (tok.empty()) return false;
  auto r = std::from_chars(tok.data(), tok.data() + tok.size(), out);
  if (r.ptr != tok.data() + tok.size()) return false;
  if (r.ec == std::errc()) return true;
  if (r.ec != std::errc::result_out_of_range) return false;
  std::string copy(tok);
  out = static_cast<Real>(std::strtod(copy.c_str(), nullptr));
  return true;
}

// Longest integer prefix of `tok` (for OBJ "12/5/7"); false when there is none.
inline bool parse_int_prefix(std::string_view tok, int64_t& out) {
  if (!tok.empty() && tok.front() == '+') tok.remove_prefix(1);
  auto r = std::from_chars(tok.data(), tok.data() + tok.size(), out);
  return r.ec == std::errc() && (r.ptr == tok.data() + tok.size() || *r.ptr == '/');
}

// A token for an error message: at most `max` characters, anything but printable ASCII as
// '?' (a message is one printable line, whatever bytes the file holds).
inline std::string quoted(std::string_view tok, size_t max = 40) {
  std::string s(tok.substr(0, max));
  for (char& c : s)
    if (static_cast<unsigned char>(c) < 32 || static_cast<unsigned char>(c) > 126) c = '?';
  return "'" + s + (tok.size() > max ? "...'" : "'");
}

// Reads the next three coordinates of `line` (consumed from it) onto `out`. Returns what
// is wrong, for the caller's "file: line N: ..." message, or "" when all three were read.
// Coordinates are read in double: the loaders round them to float only relative to the
// mesh's origin (set_model_positions).
inline std::string take_xyz(std::string_view& line, std::vector<double>& out) {
  for (int k = 0; k < 3; ++k) {
    std::string_view tok = next_token(line);
    double x;
    if (tok.empty()) return "vertex needs 3 coordinates";
    if (!parse_coord(tok, x)) return "bad vertex coordinate " + quoted(tok);
    out.push_back(x);
  }
  return "";
}

}  // namespace meshsal
