// The CLI tests under mpirun: whether they can run here, and the mpirun command line.
#pragma once
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>

#include "cli_run.h"

namespace meshsal_test {

// Prints "SKIPPED: no MPI: ..." and returns true where meshsal has no MPI or mpirun is
// missing (ctest then reports a skip).
inline bool skip_without_mpi() {
#if MESHSAL_CLI_WITH_MPI
  if (::access(MESHSAL_MPIEXEC, X_OK) == 0) return false;
  std::cout << "SKIPPED: no MPI: mpirun " << MESHSAL_MPIEXEC << " is missing\n";
#else
  std::cout << "SKIPPED: no MPI: meshsal was built without it (MESHSAL_WITH_MPI=OFF, or no MPI found)\n";
#endif
  return true;
}

// What goes before "-np N meshsal ARGS" (or MPMD parts joined by " : "): mpirun as root
// too, more ranks than cores allowed, ended after 120 s (rc 124) should it hang.
inline std::string mpirun_command() {
#if MESHSAL_CLI_WITH_MPI
  const std::string mpiexec = MESHSAL_MPIEXEC;
#else
  const std::string mpiexec = "mpirun";
#endif
  return "timeout -k 5 120 " + mpiexec + " --allow-run-as-root --oversubscribe ";
}

// "-np N meshsal ARGS": one part of an mpirun command line.
inline std::string np(int n, const std::string& args) { return "-np " + std::to_string(n) + " " + cli_path() + " " + args; }

// mpirun SPEC (np() parts, joined by " : " for MPMD) with stdout and stderr kept (in
// files under `dir`).
inline CliRun run_mpi(const std::string& spec, const std::filesystem::path& dir) {
  const std::filesystem::path out = dir / "mpi_stdout.txt", err = dir / "mpi_stderr.txt";
  const std::string cmd = mpirun_command() + spec + " > " + out.string() + " 2> " + err.string() + " < /dev/null";
  const int status = std::system(cmd.c_str());
  auto bytes = [](const std::filesystem::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
  };
  CliRun r;
  r.rc = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.out = bytes(out);
  r.err = bytes(err);
  return r;
}

}  // namespace meshsal_test
