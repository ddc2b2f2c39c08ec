// meshsal CLI: each sub-command lives in its own cmd_*.cpp and registers itself here,
// so adding a command never touches main.cpp.
#pragma once
#include <functional>
#include <stdexcept>
#include <string>

#include <CLI/CLI.hpp>

namespace meshsal::cli {

// Runs the chosen command after parsing; returns the process exit code.
using RunFn = std::function<int()>;

struct Command {
  const char* name;
  const char* help;    // one line for `meshsal --help`
  int order;           // position in `meshsal --help`
  // Adds the command's options to `sub` (bound to state the returned RunFn captures).
  std::function<RunFn(CLI::App& sub)> setup;
  // Shares its work over MPI ranks (saliency, batch). Under mpirun any other command runs
  // on rank 0 alone, as one process; the other ranks end at once (main.cpp).
  bool uses_ranks = false;
};

// A wrong combination of options, found after parsing: like a bad number, a usage error
// (main prints "error: MESSAGE (see --help)" and exits with status 2, not 1).
struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Called from a static initialiser in each cmd_*.cpp: `static bool reg = register_command({...});`
bool register_command(Command command);

}  // namespace meshsal::cli
