#include "core/number_text.h"

#include <cstdio>

namespace meshsal {

std::string number_text(double x) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%g", x);
  return buf;
}

}  // namespace meshsal
