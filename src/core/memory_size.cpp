// meshsal: parse_memory_size (meshsal.h), the one reading of a size every front end uses
// (the CLI's --memory-limit, Python's memory_limit="700M"), and its inverse for messages.
#include "core/memory_size.h"

#include <cctype>
#include <string>

#include "meshsal/meshsal.h"

namespace meshsal {
namespace {

constexpr uint64_t kMiB = uint64_t(1) << 20;

// Decimal digits times 2: the exact product of a long number and a power of two, so that
// "0.3K" is 307 bytes and "1.9999999999999999999G" truncates where the digits say.
void double_digits(std::string& digits) {
  int carry = 0;
  for (size_t i = digits.size(); i-- > 0;) {
    const int d = (digits[i] - '0') * 2 + carry;
    digits[i] = char('0' + d % 10);
    carry = d / 10;
  }
  if (carry) digits.insert(digits.begin(), char('0' + carry));
}

}  // namespace

uint64_t parse_memory_size(const std::string& text) {
  const std::string syntax = "memory size must be a decimal number of bytes with an optional K, M, G or T "
                             "(powers of 1024, e.g. 700M, 1.5G), got '" + text + "'";
  // The number: digits with at most one point, at least one digit; then the unit.
  size_t i = 0, frac_digits = 0;
  std::string digits;
  while (i < text.size() && std::isdigit(static_cast<unsigned char>(text[i]))) digits += text[i++];
  if (i < text.size() && text[i] == '.') {
    ++i;
    while (i < text.size() && std::isdigit(static_cast<unsigned char>(text[i]))) digits += text[i++], ++frac_digits;
  }
  if (digits.empty() || text.size() > 200) throw Error(syntax);
  std::string unit = text.substr(i);
  if (unit.size() == 2 && (unit[1] == 'B' || unit[1] == 'b')) unit.pop_back();  // "700MB"
  int shift = 0;
  if (unit.size() == 1) {
    const char u = char(std::toupper(static_cast<unsigned char>(unit[0])));
    shift = u == 'K' ? 10 : u == 'M' ? 20 : u == 'G' ? 30 : u == 'T' ? 40 : -1;
  }
  if (shift < 0 || unit.size() > 1) throw Error(syntax);
  if (digits.find_first_not_of('0') == std::string::npos) throw Error("memory size must be more than 0, got '" + text + "'");
  // Whole bytes: the digits times 2^shift, the fraction's digits cut off (truncation).
  for (int k = 0; k < shift; ++k) double_digits(digits);
  digits.resize(digits.size() - frac_digits);
  const size_t first = digits.find_first_not_of('0');
  digits = first == std::string::npos ? "" : digits.substr(first);
  const std::string too_large = "memory size '" + text + "' is more bytes than a 64-bit count holds";
  if (digits.size() > 20) throw Error(too_large);
  uint64_t bytes = 0;
  for (char c : digits) {
    const uint64_t d = uint64_t(c - '0');
    if (bytes > (UINT64_MAX - d) / 10) throw Error(too_large);
    bytes = bytes * 10 + d;
  }
  // A bare number is bytes: one under 1M is surely a forgotten unit (no run fits in 1M).
  const std::string number = text.substr(0, i);
  if (unit.empty() && bytes < kMiB)
    throw Error("memory size '" + text + "' is " + std::to_string(bytes) + " bytes: give a unit, e.g. " + number +
                (bytes >= 1 ? "M" : "G") + " (K, M, G or T)");
  if (bytes == 0) throw Error("memory size '" + text + "' is less than one byte");
  return bytes;
}

std::string memory_size_text(uint64_t bytes) {
  static const char units[] = "KMGT";
  for (int k = 4; k >= 1; --k) {
    const uint64_t unit = uint64_t(1) << (10 * k);
    if (bytes >= unit && bytes % unit == 0) return std::to_string(bytes / unit) + units[k - 1];
  }
  return std::to_string(bytes) + " bytes";
}

}  // namespace meshsal
