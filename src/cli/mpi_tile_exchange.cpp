#include "mpi_tile_exchange.h"

#include <cmath>

#include "mpi_world.h"

namespace meshsal::cli {

int MpiTileExchange::rank() const { return meshsal::cli::mpi_world().rank; }

int MpiTileExchange::ranks() const { return meshsal::cli::mpi_world().size; }

std::vector<std::vector<uint8_t>> MpiTileExchange::all_gather(const std::vector<uint8_t>& mine) {
  return meshsal::cli::mpi_all_gather(mine);
}

unsigned default_mpi_tiles(int ranks) {
  return unsigned(std::max(2.0, std::ceil(std::sqrt(2.0 * ranks))));
}

}  // namespace meshsal::cli
