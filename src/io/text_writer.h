// meshsal (internal): the text the OBJ and OFF writers put in a file, built in blocks of
// about 1 MiB and written as each fills. Numbers by std::to_chars: the shortest text that
// reads back to the same bits.
#pragma once
#include <charconv>
#include <cstdio>
#include <string>

#include "io/atomic_write.h"

namespace meshsal {

class TextWriter {
 public:
  TextWriter(std::FILE* f, const std::string& path, bool wide) : f_(f), path_(path), wide_(wide) { out_.reserve(1 << 20); }
  ~TextWriter() = default;

  TextWriter& operator<<(const std::string& s) { out_ += s; return *this; }
  TextWriter& operator<<(const char* s) { out_ += s; return *this; }
  TextWriter& operator<<(char c) { out_ += c; return *this; }

  template <typename T>
  void number(T value) {
    char num[64];
    const auto r = std::to_chars(num, num + sizeof num, value);
    out_.append(num, r.ptr);
  }

  // A coordinate: the shortest text of the double where the file needs double (`wide`:
  // positions_need_double) or that text has at most 9 significant digits (a value as a file
  // had it, e.g. 0.123456789: written as read); else the shortest text of its float (a
  // computed position, whose float is within 1e-7 of the diagonal). The value decides, so
  // every front end writes the same bytes for the same positions.
  void coordinate(double x) {
    char d[64];
    const auto r = std::to_chars(d, d + sizeof d, x);
    int digits = 0;
    bool leading = true;
    for (const char* c = d; c < r.ptr && *c != 'e'; ++c)
      if (*c >= '1' && *c <= '9') ++digits, leading = false;
      else if (*c == '0' && !leading) ++digits;
    if (double(float(x)) == x || !(wide_ || digits <= 9)) number(float(x));
    else out_.append(d, r.ptr);
  }

  // Ends a line; writes the block when it is full.
  void end_line() {
    out_ += '\n';
    if (out_.size() > (1 << 20) - 256) flush();
  }

  void flush() {
    write_all(f_, out_.data(), out_.size(), path_);
    out_.clear();
  }

 private:
  std::FILE* f_;
  const std::string& path_;
  bool wide_;
  std::string out_;
};

}  // namespace meshsal
