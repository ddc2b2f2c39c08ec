#include "mpi_tile_exchange.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "mpi_world.h"

namespace meshsal::cli {

int MpiTileExchange::rank() const { return meshsal::cli::mpi_world().rank; }

int MpiTileExchange::ranks() const { return meshsal::cli::mpi_world().size; }

std::vector<std::vector<uint8_t>> MpiTileExchange::all_gather(const std::vector<uint8_t>& mine) {
  return meshsal::cli::mpi_all_gather(mine);
}

std::vector<std::vector<uint8_t>> MpiTileExchange::gather(const std::vector<uint8_t>& mine, int root) {
  return meshsal::cli::mpi_gather(mine, root);
}

void begin_shared_work(const std::string& arguments, const std::string& this_run) {
  if (!mpi_world().active) return;
  mpi_begin_work();
  const auto all = mpi_all_gather(std::vector<uint8_t>(arguments.begin(), arguments.end()));
  if (std::string(all[0].begin(), all[0].end()) != arguments)
    throw meshsal::Error("the ranks were started with other arguments than rank 0's (this rank: " + this_run + ")");
}

uint64_t max_over_ranks(uint64_t value) {
  std::vector<uint8_t> bytes(sizeof value);
  std::memcpy(bytes.data(), &value, sizeof value);
  uint64_t most = 0;
  for (const auto& b : mpi_all_gather(bytes)) {
    uint64_t x = 0;
    if (b.size() == sizeof x) std::memcpy(&x, b.data(), sizeof x);
    most = std::max(most, x);
  }
  return most;
}

unsigned default_mpi_tiles(int ranks) {
  return unsigned(std::max(2.0, std::ceil(std::sqrt(2.0 * ranks))));
}

}  // namespace meshsal::cli
