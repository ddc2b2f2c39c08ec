// meshsal: a number as messages print it ("%g": 0.05, 1e+06), for the option checks of
// every layer and the command line.
#pragma once
#include <string>

namespace meshsal {

std::string number_text(double x);

}  // namespace meshsal
