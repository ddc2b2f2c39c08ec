// meshsal CLI: the MPI world the program runs in (README, "Across machines: MPI"). The
// process is under MPI only when mpirun or srun started it (their environment variables);
// otherwise, and in a build without MPI (MESHSAL_WITH_MPI unset), it runs as one process
// and never calls MPI_Init, so the CLI is unchanged where no MPI is installed or wanted.
// Only the `meshsal` program links MPI: the library and the Python module never do.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

namespace meshsal::cli {

struct MpiWorld {
  bool active = false;  // MPI_Init was called (started by mpirun/srun, built with MPI)
  int rank = 0;
  int size = 1;
  int local_size = 1;  // the ranks on this rank's machine (MPI_COMM_TYPE_SHARED), this one included
};

// The world mpi_start() found (one inactive rank 0 of 1 before it, or without MPI).
const MpiWorld& mpi_world();

// From main(), before anything else reads argv: MPI_Init when under mpirun/srun (it may
// take its own arguments out of argv). A no-op otherwise or when built without MPI.
void mpi_start(int* argc, char*** argv);

// MPI_Finalize when mpi_start() started MPI; else nothing.
void mpi_stop();

// How the ranks end when one stopped before the work (mpi_begin_work): the status every
// rank exits with, and the line this rank prints ("" on every rank but 0: printed once).
struct RanksStopped {
  int status = 0;
  std::string line;
};

// The ranks' one meeting before their work: a command that uses the ranks calls it once,
// before its first collective, when each rank has done alone the checks every rank makes
// alike (options, outputs, an input read). Returns when every rank goes on; throws
// RanksStopped when one stopped before it (main met the others here for it with
// mpi_stop_before_work), so that all end alike, quietly, without MPI_Abort. Not active:
// nothing.
void mpi_begin_work();

// Whether this rank has been to mpi_begin_work.
bool mpi_work_begun();

// From main, for a rank that stopped before mpi_begin_work (a usage error, --help, an error,
// or a command that never calls it) with `status` and the `line` it would print: meets the
// others there and returns how every rank ends: the first stopped rank's status and line
// ("meshsal (rank R): " in front unless every rank stopped with that line), the line for
// rank 0 alone.
RanksStopped mpi_stop_before_work(int status, const std::string& line);

// A rank that fails ends every rank, never leaving the others waiting in a collective:
// prints "meshsal (rank R): MESSAGE" on stderr and calls MPI_Abort(status), which ends the
// whole job with that status. When not active it prints "meshsal: MESSAGE" and exits with
// `status` (a [[noreturn]] function cannot return).
[[noreturn]] void mpi_abort(int status, const std::string& message);

// Every rank passes its bytes and receives every rank's, in rank order (at most 2 GiB in
// all). Not active: {mine}.
std::vector<std::vector<uint8_t>> mpi_all_gather(const std::vector<uint8_t>& mine);

// Every rank passes its bytes; rank `root` receives every rank's, in rank order, the others
// nothing (at most 2 GiB in all). Not active: {mine}.
std::vector<std::vector<uint8_t>> mpi_gather(const std::vector<uint8_t>& mine, int root);

// Waits for every rank. Not active: nothing.
void mpi_barrier();

// How many processes mpirun or srun started, as their environment says, whether or not
// this build has MPI (OMPI_COMM_WORLD_SIZE, PMI_SIZE; 1 where only PMIX_RANK or PMI_RANK is
// set); 0 when none started this one. A build without MPI uses it to refuse a batch that N
// copies of itself would each run whole.
int mpi_launcher_size();

// The CPU threads a rank uses by default: the machine's cores shared among the ranks on it
// (mpi_world().local_size; at least 1), so that N ranks on one machine do not start N times
// its cores. All the cores when not active.
unsigned mpi_default_threads();

// This process's rank as mpirun or srun's environment says (OMPI_COMM_WORLD_RANK,
// PMIX_RANK, PMI_RANK), without MPI_Init; 0 when none started it. A command that does not
// use the ranks runs on rank 0 alone by it.
int mpi_launcher_rank();

}  // namespace meshsal::cli
