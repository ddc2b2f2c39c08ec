// meshsal: the saliency of a TileStore's tiles (phases 0-3 of saliency_tiles.h), a tile
// at a time with each tile's state on disk between phases, and the per-vertex results
// read back in the input's order: what saliency_file() writes and simplify_file() weighs.
#pragma once
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "tiles/tile_store.h"
#include "meshsal/meshsal.h"

namespace meshsal {

// Phases 0-3 over this process's share of the store's tiles (options.exchange shares them
// and reduces the per-scale scalars); each tile's results stay in its file. Fills
// report's counts, pairs, saliency range and stages (from "curvature" on). The results
// hold S and Sm, and with `scales` (--dump-scales) the curvature and raw maps too.
void tile_saliency(const TileStore& store, const SaliencyOptions& options, OutOfCoreReport& report, bool scales);

// What saliency_file() writes, from the store's tile results (tile_saliency above, with
// report's range): the vertices a block at a time in the input's order, then the triangles.
void write_saliency_output(const std::string& output, const TileStore& store, const SaliencyOptions& options,
                           const OutOfCoreOptions& ooc, const OutOfCoreReport& report,
                           const std::function<void(const char*, double)>& progress);

// Tile t's results file.
std::string tile_result_file(const TileStore& store, size_t t);

// The tiles' results in the input's vertex order, a block at a time: per vertex of
// [first, first + count), kResultWidth + scales values: S, Sm (0 unless options.smoothed),
// curvature, then the raw map of each scale (0 unless tile_saliency kept them: `kept`);
// point[v] = 1 where a tile owns the vertex (a mesh point), else its values are 0. Each tile's file holds its own points' records in
// vertex order, so a cursor per tile reads every file once over ascending blocks, and a
// block no record of a tile falls in does not open its file (blocks may skip vertices; a
// block before the last one read is an error).
constexpr size_t kResultWidth = 3;
class TileResultReader {
 public:
  TileResultReader(const TileStore& store, size_t scales, bool kept);
  void read(uint64_t first, size_t count, std::vector<double>& values, std::vector<uint8_t>& point);

 private:
  const TileStore& store_;
  size_t scales_;
  bool kept_;
  uint64_t next_ = 0;              // the first vertex the next block may start at
  std::vector<uint64_t> offset_;   // per tile: the bytes of its file read so far
  std::vector<uint64_t> ahead_;    // per tile: its next record's vertex (0: not known yet; UINT64_MAX: none)
};

}  // namespace meshsal
