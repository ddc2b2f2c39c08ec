// meshsal: the one exception type the library throws for bad input or a failed device.
// Its message is a single line meant for the user (the CLI prints it after "error: ").
#pragma once
#include <stdexcept>
#include <string>

namespace meshsal {

struct Error : std::runtime_error {
  using std::runtime_error::runtime_error;
};

}  // namespace meshsal
