// meshsal CLI: MpiWorld (see mpi_world.h). Everything MPI is behind MESHSAL_WITH_MPI, so a
// build without it compiles this file into the one-process answers.
#include "mpi_world.h"

#include <algorithm>
#include <climits>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>

#if MESHSAL_WITH_MPI
// The C API only: mpi.h would otherwise bring Open MPI's C++ bindings (and their library)
// into a C++ file.
#define OMPI_SKIP_MPICXX 1
#define MPICH_SKIP_MPICXX 1
#include <mpi.h>
#endif

namespace meshsal::cli {
namespace {

MpiWorld& world() {
  static MpiWorld w;
  return w;
}

}  // namespace

const MpiWorld& mpi_world() { return world(); }

int mpi_launcher_size() {
  // Open MPI's mpirun, PMIx (srun --mpi=pmix, Open MPI 5), PMI/PMI-2 (MPICH's hydra, srun
  // --mpi=pmi2). SLURM_PROCID alone is not enough: a plain srun of a serial job sets it too.
  for (const char* v : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE"})
    if (const char* n = std::getenv(v)) return std::max(1, std::atoi(n));
  for (const char* v : {"PMIX_RANK", "PMI_RANK"})
    if (std::getenv(v)) return 1;
  return 0;
}

void mpi_start(int* argc, char*** argv) {
#if MESHSAL_WITH_MPI
  if (world().active || mpi_launcher_size() == 0) return;
  // FUNNELED: only the main thread calls MPI; the loader and the library's workers are
  // threads too, which MPI_THREAD_SINGLE would not allow.
  int provided = 0;
  MPI_Init_thread(argc, argv, MPI_THREAD_FUNNELED, &provided);
  MpiWorld& w = world();
  w.active = true;
  MPI_Comm_rank(MPI_COMM_WORLD, &w.rank);
  MPI_Comm_size(MPI_COMM_WORLD, &w.size);
#else
  (void)argc;
  (void)argv;
#endif
}

void mpi_stop() {
#if MESHSAL_WITH_MPI
  if (!world().active) return;
  MPI_Finalize();
  world().active = false;
#endif
}

void mpi_abort(int status, const std::string& message) {
  std::fflush(stdout);
#if MESHSAL_WITH_MPI
  if (world().active) {
    std::fprintf(stderr, "meshsal (rank %d): %s\n", world().rank, message.c_str());
    std::fflush(stderr);
    MPI_Abort(MPI_COMM_WORLD, status);
  }
#endif
  std::fprintf(stderr, "meshsal: %s\n", message.c_str());
  std::exit(status);
}

std::vector<std::vector<uint8_t>> mpi_all_gather(const std::vector<uint8_t>& mine) {
#if MESHSAL_WITH_MPI
  if (world().active) {
    const int n = world().size;
    // Sizes first, then the bytes at their offsets (Allgatherv counts are ints).
    const unsigned long long my_size = mine.size();
    std::vector<unsigned long long> sizes(static_cast<size_t>(n), 0);
    MPI_Allgather(&my_size, 1, MPI_UNSIGNED_LONG_LONG, sizes.data(), 1, MPI_UNSIGNED_LONG_LONG, MPI_COMM_WORLD);
    std::vector<int> counts(static_cast<size_t>(n)), offsets(static_cast<size_t>(n));
    unsigned long long total = 0;
    for (int r = 0; r < n; ++r) {
      offsets[size_t(r)] = int(total);
      counts[size_t(r)] = int(sizes[size_t(r)]);
      total += sizes[size_t(r)];
      // Every rank sees the same sizes, so every rank throws here alike (no one waits).
      if (total > (unsigned long long)INT_MAX)
        throw std::runtime_error("mpi_all_gather: more than 2 GiB from all ranks together");
    }
    std::vector<uint8_t> all(size_t(total) + 1);  // +1: a valid pointer when empty
    MPI_Allgatherv(mine.data(), int(my_size), MPI_BYTE, all.data(), counts.data(), offsets.data(), MPI_BYTE,
                   MPI_COMM_WORLD);
    std::vector<std::vector<uint8_t>> out(static_cast<size_t>(n));
    for (int r = 0; r < n; ++r)
      out[size_t(r)].assign(all.begin() + offsets[size_t(r)], all.begin() + offsets[size_t(r)] + counts[size_t(r)]);
    return out;
  }
#endif
  return {mine};
}

void mpi_barrier() {
#if MESHSAL_WITH_MPI
  if (world().active) MPI_Barrier(MPI_COMM_WORLD);
#endif
}

}  // namespace meshsal::cli
