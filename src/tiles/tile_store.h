// meshsal: a mesh cut into tiles on disk, for saliency under a memory limit (out of core).
// Built by streaming the input (binary PLY; other formats are converted once) through a
// few passes, each holding at most a block of vertices in memory:
//   A  vertices as read to xyz (float or double: xyz_float), faces fan-triangulated to tri.u32, and one bit
//      per vertex for "referenced by a face";
//   B  the mesh points' bounding box in the model's coordinates -> the origin (as the
//      loaders set it), local float positions to pos.f32, their bounding box and a coarse
//      histogram of the points -> the tile count that fits the limit (TilePlan);
//   C  every triangle to the bucket file of each tile one of its corners lies in.
// store_tile_source() then hands each tile's bucket, with the vertex positions read from
// pos.f32, to phase C (saliency_tiles.h), which keeps the tile's points for the others.
#pragma once
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "tiles/scratch_files.h"
#include "tiles/saliency_tiles.h"

namespace meshsal {

// What a tile's run costs at its peak per point: a point of its own (phase C's curvature
// from the bucket, phase 1's raw maps and rings, phase 3's results) more than a halo point
// (phase 1's source only: its position, curvature and a share of the averages: one sigma's
// at a time with the fast method, every sigma's at once with the exact sweep). Measured
// (peak resident over the base): the fast method on igea_loop2 x4 (8.6M points) in 8 tiles
// peaked at 447 MiB for a largest tile of 1.71M own and 2.40M halo points; one tile of
// igea_134k at about 150 bytes a point (fast) and 130 (exact). Since a tile's files are
// written while the next one is computed (and each thread's heap keeps what it freed), the
// same run peaks at 489-596 MiB: 280 bytes an own point keeps the estimate above it. The
// tile count is chosen so the largest tile's estimate fits. For the default scales' 8
// sigmas (plan_cost adds what more sigmas cost).
constexpr double kOwnBytesPerVertex = 280;
constexpr double kHaloBytesPerVertex = 100;     // exact
constexpr double kFastHaloBytesPerVertex = 60;  // fast
// The most work a tiling may cost, in tile points (halos included) per mesh point: finer
// tiles than that barely shrink (the halo stays the filter's reach) and only slow down.
constexpr double kMaxTileWork = 40;
// The process before any tile: the program, its libraries and the buffers of the passes.
constexpr uint64_t kBaseBytes = uint64_t(28) << 20;

// Mesh points per bin of a 128^3 grid over their bounding box (8 MB): what a tile's box
// holds, to choose a tiling before any tile is built.
struct PointHistogram {
  static constexpr int kBins = 128;
  BoundingBox box;
  double bin[3] = {1, 1, 1};
  std::vector<uint32_t> count = std::vector<uint32_t>(size_t(kBins) * kBins * kBins, 0);
  int bin_of(double x, int a) const {
    return int(std::clamp(std::floor((x - box.min[a]) / bin[a]), 0.0, double(kBins - 1)));
  }
  void add(const float* p) {
    count[(size_t(bin_of(p[2], 2)) * kBins + bin_of(p[1], 1)) * kBins + bin_of(p[0], 0)]++;
  }
  // The points in the bins that meet b: at least the points inside it.
  uint64_t within(const BoundingBox& b) const;
};

struct TileStore {
  explicit TileStore(const std::string& temp_parent) : dir(temp_parent) {}
  // A store of another's folder (a rank in a thread: rank 0's), none made for it.
  TileStore(const std::string& folder, ScratchDir::Borrowed b) : dir(folder, b) {}
  ScratchDir dir;
  std::string input;
  uint64_t vertices = 0, triangles = 0, points = 0;
  bool double_positions = false;  // the input stored double x, y, z
  double origin[3] = {0, 0, 0};
  TilePlan plan;
  BoundingBox box;           // of the mesh points, in local (float) coordinates
  PointHistogram histogram;  // of the mesh points
  uint64_t largest_tile_estimate = 0;  // bytes, the largest tile's estimate
  size_t block = 0;                    // vertices per block of the passes
  int bucket_ranks = 1;                // the ranks that filled buckets (a file each per tile)
  int readers = 1;                     // the ranks (or ranks in threads) that read the input, each its share
  // xyz, the coordinates as read: as floats where the streamed file's fit in floats (half
  // the bytes to write and read again, the same values), else as doubles.
  bool xyz_float = false;
  size_t xyz_bytes() const { return xyz_float ? 12 : 24; }
};

// What a store is built for: the saliency's tiles (pass C's buckets, the tile count that
// fits the limit), or only passes A and B (the files, the box and the histogram: a
// simplification without saliency groups the triangles itself).
enum class StoreUse { SaliencyTiles, FilesOnly };

// Streams `input` into tiles under `memory_limit` bytes (0: no limit, `tiles` along the
// longest axis, else the fewest tiles that fit; at least `tiles`). Throws Error naming the
// smallest workable limit when even the finest tiling does not fit. `progress` (may be
// empty) gets each pass's name and fraction.
void build_tile_store(TileStore& store, const std::string& input, const SaliencyOptions& options,
                      uint64_t memory_limit, unsigned tiles,
                      const std::function<void(const char*, double)>& progress,
                      StoreUse use = StoreUse::SaliencyTiles);

// build_tile_store's steps, for share_tile_store: the input as a binary PLY the passes
// stream (store.input: itself, or another format converted once into the folder, in double;
// converted_wide: the converted mesh's own precision, -1 for a PLY as it is), then the
// passes over it. With an exchange every rank runs its share of a file that reads in
// ranges (PlyStream::ranged): its vertices, its faces and its triangles' buckets; the
// boxes, counts and histogram joined (the histogram on rank 0, which picks the tiling).
// memory_parts: how many ranks share this process's limit (ranks in threads: each sizes
// its buffers for its part).
void store_input(TileStore& store, const std::string& input, int& converted_wide);
void build_store_passes(TileStore& store, const std::string& input, const SaliencyOptions& options,
                        uint64_t memory_limit, unsigned tiles,
                        const std::function<void(const char*, double)>& progress, StoreUse use, int converted_wide,
                        TileExchange* exchange, unsigned memory_parts);

// build_tile_store under an exchange (options.exchange), in the one folder they all reach
// (rank 0's): a binary PLY that reads in ranges is built by every rank, each its share; any
// other input by rank 0, whose description the others take (its folder, counts, origin,
// boxes and plan; not the histogram). An error on any rank is thrown on every rank. Without
// an exchange, a PLY that reads in ranges is built by ranks in threads of this process, one
// per thread (options.threads), sharing its limit; anything else by build_tile_store.
void share_tile_store(TileStore& store, const std::string& input, const SaliencyOptions& options,
                      uint64_t memory_limit, unsigned tiles,
                      const std::function<void(const char*, double)>& progress,
                      StoreUse use = StoreUse::SaliencyTiles);

// "123M": bytes as --memory-limit takes them, rounded up (the errors naming a limit).
std::string mib_text(uint64_t bytes);

// The store's buckets and positions, for phase C (tile_curvature).
TileSource store_tile_source(const TileStore& store);

// The doubles as read of vertices [first, first + count) (the output's positions).
void read_source_positions(const TileStore& store, uint64_t first, size_t count, double* out);

// Triangles [first, first + count) of the triangulated faces.
void read_triangles(const TileStore& store, uint64_t first, size_t count, uint32_t* out);

}  // namespace meshsal
