// meshsal: the reductions of a tiled saliency run over the processes sharing it
// (TileExchange; none: this process alone), one per phase, for every driver
// (saliency_tiled.cpp in memory, saliency_out_of_core.cpp on disk).
#pragma once
#include <cstdint>
#include <functional>
#include <vector>

#include "meshsal/meshsal.h"
#include "tiles/saliency_tiles.h"

namespace meshsal {

// Runs `step` on rank 0 alone (without an exchange: here) and tells every process how it
// went: an Error there is thrown on every process with rank 0's message (rank 0 rethrows
// its own), so none is left waiting in a later collective and each says the real reason.
void lead_step(TileExchange* exchange, const std::function<void()>& step);

// Runs `step` on every process and tells each how all went: a failure on any is thrown on
// every one, with the message of the lowest rank that failed (a bad face seen by one rank
// stops them all with its reason; a rank cancelled throws its Cancelled). Every exception
// is caught first, so no process is left waiting in a later collective.
void all_step(TileExchange* exchange, const std::function<void()>& step);

// Every process's bytes (just `mine` without an exchange).
std::vector<std::vector<uint8_t>> tile_gather(TileExchange* exchange, const std::vector<uint8_t>& mine);

// Phase 0: the whole mesh's occupied cells per sigma from every process's tiles (`mine`:
// this process's, add_tile_cells): their inner counts summed, plus the distinct keys among
// all their across lists.
std::vector<uint64_t> whole_mesh_cells(TileExchange* exchange, const TileCells& mine);

// Phase 1: each scale's maximum over every process's (lowest vertex on ties), and the sum
// of their pairs.
void reduce_scale_max(TileExchange* exchange, std::vector<ScaleMax>& max, uint64_t& pairs);

// Phase 2: each scale's mbar from every process's local maxima (`mine[scale]`): gathered
// on rank 0 alone (TileExchange::gather), which sums them and hands out the sums.
std::vector<double> reduce_mbar(TileExchange* exchange, std::vector<std::vector<LocalMax>> mine,
                                const std::vector<ScaleMax>& max);

}  // namespace meshsal
