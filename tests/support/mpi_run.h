// The CLI tests under mpirun: whether they can run here, and the mpirun command line.
#pragma once
#include <unistd.h>

#include <iostream>
#include <string>

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

}  // namespace meshsal_test
