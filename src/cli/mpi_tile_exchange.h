// meshsal CLI: the library's TileExchange over the MPI world (mpi_world.h), so that
// `mpirun -np N meshsal saliency` (and simplify) shares the tiles over the ranks; and what
// those commands do alike around it.
#pragma once
#include <cstdint>
#include <string>

#include "meshsal/meshsal.h"

namespace meshsal::cli {

class MpiTileExchange : public meshsal::TileExchange {
 public:
  int rank() const override;
  int ranks() const override;
  std::vector<std::vector<uint8_t>> all_gather(const std::vector<uint8_t>& mine) override;
  std::vector<std::vector<uint8_t>> gather(const std::vector<uint8_t>& mine, int root) override;
};

// Under mpirun, once this rank has read its input: the ranks meet (mpi_begin_work: one
// that failed before stops all, quietly), then every rank must run the same computation:
// `arguments` (what decides it) must be rank 0's, else an Error naming `this_run`. Not
// under MPI: nothing.
void begin_shared_work(const std::string& arguments, const std::string& this_run);

// The largest of every rank's `value` (this process's alone without MPI): the peak
// resident memory a shared run reports.
uint64_t max_over_ranks(uint64_t value);

// Tiles along the longest axis when mpirun starts N ranks and --tiles is not given: the
// fewest with at least 2 N tiles on a surface (N^2 of them meet it), so every rank has work.
unsigned default_mpi_tiles(int ranks);

}  // namespace meshsal::cli
