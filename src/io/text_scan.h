// meshsal: tiny line/token scanner shared by the text parsers (OBJ, OFF, ascii PLY).
// Works on the file bytes in memory; numbers via std::from_chars (no iostreams, no locale).
#pragma once
#include <charconv>
#include <cstdlib>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "meshsal/meshsal.h"

namespace meshsal {

struct TextScan {
  std::string_view text;
  size_t pos = 0;
  size_t line_no = 0;  // 1-based number of the line last returned by next_line

  explicit TextScan(std::string_view t) : text(t) {}

  bool at_end() const { return pos >= text.size(); }

  // The next line without its "\n" / "\r\n"; false at the end of the text.
  bool next_line(std::string_view& line) {
    if (pos >= text.size()) return false;
    size_t end = text.find('\n', pos);
    if (end == std::string_view::npos) end = text.size();
    line = text.substr(pos, end - pos);
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    pos = end + 1;
    ++line_no;
    return true;
  }
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
inline bool parse_coord(std::string_view tok, float& out) {
  if (!tok.empty() && tok.front() == '+') tok.remove_prefix(1);
  if (tok.empty()) return false;
  auto r = std::from_chars(tok.data(), tok.data() + tok.size(), out);
  if (r.ptr != tok.data() + tok.size()) return false;
  if (r.ec == std::errc()) return true;
  if (r.ec != std::errc::result_out_of_range) return false;
  std::string copy(tok);
  out = static_cast<float>(std::strtod(copy.c_str(), nullptr));
  return true;
}

// Longest integer prefix of `tok` (for OBJ "12/5/7"); false when there is none.
inline bool parse_int_prefix(std::string_view tok, int64_t& out) {
  if (!tok.empty() && tok.front() == '+') tok.remove_prefix(1);
  auto r = std::from_chars(tok.data(), tok.data() + tok.size(), out);
  return r.ec == std::errc() && (r.ptr == tok.data() + tok.size() || *r.ptr == '/');
}

inline std::string quoted(std::string_view tok) {
  if (tok.size() > 40) return "'" + std::string(tok.substr(0, 40)) + "...'";
  std::string s(tok);
  for (char& c : s)
    if (static_cast<unsigned char>(c) < 32 || static_cast<unsigned char>(c) > 126) c = '?';
  return "'" + s + "'";
}

// Reads the next three coordinates of `line` (consumed from it) onto `out`. Returns what
// is wrong, for the caller's "file: line N: ..." message, or "" when all three were read.
inline std::string take_xyz(std::string_view& line, std::vector<float>& out) {
  for (int k = 0; k < 3; ++k) {
    std::string_view tok = next_token(line);
    float x;
    if (tok.empty()) return "vertex needs 3 coordinates";
    if (!parse_coord(tok, x)) return "bad vertex coordinate " + quoted(tok);
    out.push_back(x);
  }
  return "";
}

}  // namespace meshsal
