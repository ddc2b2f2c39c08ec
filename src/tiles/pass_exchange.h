// meshsal (internal): what the processes that share a tiled simplification exchange in each
// pass (SimplifyOptions::exchange): process r runs the groups g with g % ranks == r, and
// every process gets every group's facts and pieces, so all hold the mesh one process makes.
// Without an exchange each function is this process alone (it runs every group).
#pragma once
#include <cstdint>
#include <vector>

#include "meshsal/meshsal.h"
#include "tiles/tile_pass.h"
#include "tiles/tile_pieces.h"

namespace meshsal {
namespace detail {

// Whether this process runs group g.
bool runs_group(const TileExchange* exchange, size_t g);

// Per group values (faces, first-pass goals) that each process filled for its own groups
// (runs_group; the others' entries any value): every group's, from the process that ran it.
void share_group_values(TileExchange* exchange, std::vector<uint64_t>& values);

// The same for each group's collapse levels (tile_pass.h).
void share_group_levels(TileExchange* exchange, std::vector<std::vector<double>>& levels);

// What a group's simplification gave: its piece (no guards) and the ids it freed.
struct GroupOutcome {
  TilePiece piece;
  std::vector<uint32_t> freed;
};

// Each process's outcomes of its own groups (`outcomes[g]`, empty elsewhere) and its totals
// of the pass: every group's outcome, from the process that ran it, and the totals of all
// processes. `attributes`: the vertex attributes a piece carries.
void share_group_outcomes(TileExchange* exchange, std::vector<GroupOutcome>& outcomes, PassTotals& pass,
                          size_t attributes);

// The pass totals of every process (collapses and refusals summed, the largest error).
PassTotals share_totals(TileExchange* exchange, const PassTotals& mine);

// `more` added to `into` (collapses and refusals summed, the largest error).
void add_totals(PassTotals& into, const PassTotals& more);

// Rank 0's values (the processes that did not compute them get them), and a barrier.
void share_rank0_values(TileExchange* exchange, std::vector<uint64_t>& values);

// Rank 0's value of a count (the processes that did not compute it get it), and a barrier.
uint64_t share_rank0_value(TileExchange* exchange, uint64_t value);

}  // namespace detail
}  // namespace meshsal
