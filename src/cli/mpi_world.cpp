// meshsal CLI: MpiWorld (see mpi_world.h). Everything MPI is behind MESHSAL_WITH_MPI, so a
// build without it compiles this file into the one-process answers.
#include "mpi_world.h"

#include "core/parallel.h"

#include <algorithm>
#include <thread>
#include <climits>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <string>

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
  // What "all cores" means for this rank's helpers too, not only its requests' threads.
  set_process_threads(mpi_default_threads());
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

#if MESHSAL_WITH_MPI
namespace {

// Where each rank's bytes go in a gathered buffer: every rank's size (an Allgather, so every
// rank sees the same sizes and throws alike past 2 GiB, the counts being ints), then the
// counts and offsets Gatherv and Allgatherv take.
struct ByteLayout {
  std::vector<int> counts, offsets;
  size_t total = 0;
};

ByteLayout byte_layout(size_t mine, const char* who) {
  const int n = world().size;
  const unsigned long long my_size = mine;
  std::vector<unsigned long long> sizes(static_cast<size_t>(n), 0);
  MPI_Allgather(&my_size, 1, MPI_UNSIGNED_LONG_LONG, sizes.data(), 1, MPI_UNSIGNED_LONG_LONG, MPI_COMM_WORLD);
  ByteLayout l;
  unsigned long long total = 0;
  for (int r = 0; r < n; ++r) {
    l.offsets.push_back(int(total));
    l.counts.push_back(int(sizes[size_t(r)]));
    total += sizes[size_t(r)];
    if (total > (unsigned long long)INT_MAX)
      throw std::runtime_error(std::string(who) + ": more than 2 GiB from all ranks together");
  }
  l.total = size_t(total);
  return l;
}

// The buffer cut back into each rank's bytes.
std::vector<std::vector<uint8_t>> split(const std::vector<uint8_t>& all, const ByteLayout& l) {
  std::vector<std::vector<uint8_t>> out;
  for (size_t r = 0; r < l.counts.size(); ++r)
    out.emplace_back(all.begin() + l.offsets[r], all.begin() + l.offsets[r] + l.counts[r]);
  return out;
}

}  // namespace
#endif

std::vector<std::vector<uint8_t>> mpi_all_gather(const std::vector<uint8_t>& mine) {
#if MESHSAL_WITH_MPI
  if (world().active) {
    const ByteLayout l = byte_layout(mine.size(), "mpi_all_gather");
    std::vector<uint8_t> all(l.total + 1);  // +1: a valid pointer when empty
    MPI_Allgatherv(mine.data(), int(mine.size()), MPI_BYTE, all.data(), l.counts.data(), l.offsets.data(), MPI_BYTE,
                   MPI_COMM_WORLD);
    return split(all, l);
  }
#endif
  return {mine};
}

std::vector<std::vector<uint8_t>> mpi_gather(const std::vector<uint8_t>& mine, int root) {
#if MESHSAL_WITH_MPI
  if (world().active) {
    const ByteLayout l = byte_layout(mine.size(), "mpi_gather");
    const bool is_root = world().rank == root;
    std::vector<uint8_t> all(is_root ? l.total + 1 : 1);  // only the root receives the bytes
    MPI_Gatherv(mine.data(), int(mine.size()), MPI_BYTE, all.data(), l.counts.data(), l.offsets.data(), MPI_BYTE, root,
                MPI_COMM_WORLD);
    if (!is_root) return {};
    return split(all, l);
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
