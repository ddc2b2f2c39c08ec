// meshsal CLI: the library's TileExchange over the MPI world (mpi_world.h), so that
// `mpirun -np N meshsal saliency` shares the tiles over the ranks.
#pragma once
#include "meshsal/meshsal.h"

namespace meshsal::cli {

class MpiTileExchange : public meshsal::TileExchange {
 public:
  int rank() const override;
  int ranks() const override;
  std::vector<std::vector<uint8_t>> all_gather(const std::vector<uint8_t>& mine) override;
};

// Tiles along the longest axis when mpirun starts N ranks and --tiles is not given: the
// fewest with at least 2 N tiles on a surface (N^2 of them meet it), so every rank has work.
unsigned default_mpi_tiles(int ranks);

}  // namespace meshsal::cli
