// meshsal: a number as messages print it ("%g": 0.05, 1e+06), for the option checks of
// every layer and the command line.
#pragma once
#include <string>

namespace meshsal {

std::string number_text(double x);

// The same with `digits` significant digits ("%.*g"), for figures printed in full.
std::string number_text(double x, int digits);

}  // namespace meshsal
