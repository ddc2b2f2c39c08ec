// meshsal CLI: MpiWorld (see mpi_world.h). Everything MPI is behind MESHSAL_WITH_MPI, so a
// build without it compiles this file into the one-process answers.
#include "mpi_world.h"

#include <algorithm>
#include <thread>
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

bool work_begun = false;

// The meeting before the work: every rank's [stopped, status, line...], in rank order; how
// the ranks end when one stopped.
bool meet_before_work(bool stopped, int status, const std::string& line, RanksStopped* out) {
  work_begun = true;
  std::vector<uint8_t> mine{uint8_t(stopped), uint8_t(status)};
  mine.insert(mine.end(), line.begin(), line.end());
  const std::vector<std::vector<uint8_t>> all = mpi_all_gather(mine);
  int first = -1;
  bool alike = true;
  for (size_t r = 0; r < all.size(); ++r) {
    const bool s = all[r].size() >= 2 && all[r][0];
    if (s && first < 0) first = int(r);
    alike = alike && s && all[r] == all[0];
  }
  if (first < 0) return false;
  const std::vector<uint8_t>& f = all[size_t(first)];
  std::string said(f.begin() + 2, f.end());
  if (!alike && !said.empty()) said = "meshsal (rank " + std::to_string(first) + "): " + said;
  out->status = f[1];
  out->line = world().rank == 0 ? said : "";
  return true;
}

}  // namespace

void mpi_begin_work() {
  if (!world().active || work_begun) return;
  RanksStopped stop;
  if (meet_before_work(false, 0, "", &stop)) throw stop;
}

bool mpi_work_begun() { return work_begun; }

RanksStopped mpi_stop_before_work(int status, const std::string& line) {
  RanksStopped stop{status, line};
  if (world().active && !work_begun) meet_before_work(true, status, line, &stop);
  return stop;
}

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

int mpi_launcher_rank() {
  if (mpi_launcher_size() == 0) return 0;
  for (const char* v : {"OMPI_COMM_WORLD_RANK", "PMIX_RANK", "PMI_RANK"})
    if (const char* n = std::getenv(v)) return std::max(0, std::atoi(n));
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
  // The ranks that share this machine (and so its cores).
  MPI_Comm node;
  MPI_Comm_split_type(MPI_COMM_WORLD, MPI_COMM_TYPE_SHARED, w.rank, MPI_INFO_NULL, &node);
  MPI_Comm_size(node, &w.local_size);
  MPI_Comm_free(&node);
#else
  (void)argc;
  (void)argv;
#endif
}

unsigned mpi_default_threads() {
  const unsigned cores = std::max(1u, std::thread::hardware_concurrency());
  const MpiWorld& w = world();
  if (!w.active) return cores;
  return std::max(1u, cores / unsigned(std::max(1, w.local_size)));
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

std::vector<std::vector<uint8_t>> mpi_gather(const std::vector<uint8_t>& mine, int root) {
#if MESHSAL_WITH_MPI
  if (world().active) {
    const int n = world().size;
    // Every rank learns the sizes (so every rank throws alike past 2 GiB); only the root the
    // bytes.
    const unsigned long long my_size = mine.size();
    std::vector<unsigned long long> sizes(static_cast<size_t>(n), 0);
    MPI_Allgather(&my_size, 1, MPI_UNSIGNED_LONG_LONG, sizes.data(), 1, MPI_UNSIGNED_LONG_LONG, MPI_COMM_WORLD);
    std::vector<int> counts(static_cast<size_t>(n)), offsets(static_cast<size_t>(n));
    unsigned long long total = 0;
    for (int r = 0; r < n; ++r) {
      offsets[size_t(r)] = int(total);
      counts[size_t(r)] = int(sizes[size_t(r)]);
      total += sizes[size_t(r)];
      if (total > (unsigned long long)INT_MAX)
        throw std::runtime_error("mpi_gather: more than 2 GiB from all ranks together");
    }
    const bool is_root = world().rank == root;
    std::vector<uint8_t> all(is_root ? size_t(total) + 1 : 1);
    MPI_Gatherv(mine.data(), int(my_size), MPI_BYTE, all.data(), counts.data(), offsets.data(), MPI_BYTE, root,
                MPI_COMM_WORLD);
    std::vector<std::vector<uint8_t>> out;
    if (is_root)
      for (int r = 0; r < n; ++r)
        out.emplace_back(all.begin() + offsets[size_t(r)], all.begin() + offsets[size_t(r)] + counts[size_t(r)]);
    return out;
  }
#endif
  (void)root;
  return {mine};
}

void mpi_barrier() {
#if MESHSAL_WITH_MPI
  if (world().active) MPI_Barrier(MPI_COMM_WORLD);
#endif
}

}  // namespace meshsal::cli
