// share_tile_store (tile_store.h): every rank builds its share of the store from an input
// that reads in ranges; otherwise rank 0 builds it and the others adopt its description.
#include <algorithm>
#include <memory>
#include <string>
#include <vector>

#include "core/parallel.h"
#include "core/release_memory.h"
#include "io/ply_stream.h"
#include "tiles/tile_bytes.h"
#include "tiles/tile_reduce.h"
#include "tiles/thread_ranks.h"
#include "tiles/tile_store.h"

namespace meshsal {

namespace {

// The store's description, from rank 0 to the others (they read the same files).
TileBytes describe(const TileStore& s) {
  TileBytes b;
  std::vector<uint8_t> dir(s.dir.path().begin(), s.dir.path().end());
  b.put(dir);
  b.put(s.vertices);
  b.put(s.triangles);
  b.put(s.points);
  b.put(uint8_t(s.double_positions));
  for (double o : s.origin) b.put(o);
  b.put(s.largest_tile_estimate);
  b.put(uint64_t(s.block));
  b.put(s.plan.tile_edge);
  for (int a = 0; a < 3; ++a) b.put(s.plan.box.min[a]), b.put(s.plan.box.max[a]), b.put(s.plan.tiles[a]);
  b.put(s.plan.query_margin);
  b.put(s.plan.source_margin);
  b.put(s.plan.eps);
  for (int a = 0; a < 3; ++a) b.put(s.box.min[a]), b.put(s.box.max[a]);
  b.put(int32_t(s.bucket_ranks));
  b.put(uint8_t(s.xyz_float));
  return b;
}

void adopt(TileStore& s, const std::vector<uint8_t>& bytes, const SaliencyOptions& options) {
  TileBytesReader in{bytes};
  const std::vector<uint8_t> dir = in.get_vector<uint8_t>();
  s.dir.borrow(std::string(dir.begin(), dir.end()));
  s.vertices = in.get<uint64_t>();
  s.triangles = in.get<uint64_t>();
  s.points = in.get<uint64_t>();
  s.double_positions = in.get<uint8_t>() != 0;
  for (double& o : s.origin) o = in.get<double>();
  s.largest_tile_estimate = in.get<uint64_t>();
  s.block = size_t(in.get<uint64_t>());
  const double edge = in.get<double>();
  BoundingBox box;
  int tiles[3];
  for (int a = 0; a < 3; ++a) box.min[a] = in.get<double>(), box.max[a] = in.get<double>(), tiles[a] = in.get<int>();
  s.plan = make_tile_plan(box, s.points, options, 1);
  s.plan.tile_edge = edge;
  for (int a = 0; a < 3; ++a) s.plan.tiles[a] = tiles[a];
  s.plan.query_margin = in.get<double>();
  s.plan.source_margin = in.get<double>();
  s.plan.eps = in.get<double>();
  for (int a = 0; a < 3; ++a) s.box.min[a] = in.get<double>(), s.box.max[a] = in.get<double>();
  s.bucket_ranks = in.get<int32_t>();
  s.xyz_float = in.get<uint8_t>() != 0;
}

// What a rank in a thread holds beyond the first's while the store is built: its reading
// buffers (measured about 5 MiB) and its histogram (8 MiB), besides its point bits.
constexpr uint64_t kThreadRankBytes = uint64_t(16) << 20;
// The most ranks in threads: reading the input, a pass over a file, gains little from more
// (the disk), while each holds its buffers.
constexpr unsigned kMaxThreadRanks = 4;

// The input in place (store_input) and whether it reads in ranges (PlyStream::ranged); for
// ranks that write their ranges of the store's files, those files made first.
bool prepare_input(TileStore& store, const std::string& input, int& converted_wide, bool shared) {
  store_input(store, input, converted_wide);
  const bool ranged = PlyStream(store.input).ranged();
  if (ranged && shared)
    for (const char* name : {"xyz", "tri.u32", "pos.f32"}) ScratchWriter(store.dir.file(name)).close();
  return ranged;
}

// One process: a file that reads in ranges built by ranks in threads, one per thread (the
// input's reading and the positions on every core; the buckets by rank 0 on every thread),
// all in rank 0's folder; anything else read front to back.
void build_on_threads(TileStore& store, const std::string& input, const SaliencyOptions& options,
                      uint64_t memory_limit, unsigned tiles, const std::function<void(const char*, double)>& progress,
                      StoreUse use) {
  int converted_wide = -1;
  const unsigned threads = std::min(kMaxThreadRanks, resolve_threads(options.threads));
  const bool ranged = prepare_input(store, input, converted_wide, threads > 1);
  // Each rank beyond the first holds its own reading buffers, histogram and point bits:
  // where the passes' share of the limit (all of it but pass C's block, a quarter, and
  // bucket buffers, an eighth) leaves no room for them beside the program, one rank reads.
  const uint64_t per_rank = kThreadRankBytes + PlyStream(store.input).vertex_count() / 8;
  const bool room = !memory_limit || (threads - 1) * per_rank + kBaseBytes <= memory_limit / 8 * 5;
  if (threads <= 1 || !ranged || !room) {
    build_store_passes(store, input, options, memory_limit, tiles, progress, use, converted_wide, nullptr, 1);
    return;
  }
  std::vector<std::unique_ptr<TileStore>> others;
  for (unsigned r = 1; r < threads; ++r) {
    others.push_back(std::make_unique<TileStore>(store.dir.path(), ScratchDir::Borrowed{}));
    others.back()->input = store.input;
  }
  run_thread_ranks(int(threads), [&](TileExchange& ex) {
    TileStore& mine = ex.rank() == 0 ? store : *others[size_t(ex.rank() - 1)];
    build_store_passes(mine, input, options, memory_limit, tiles, ex.rank() == 0 ? progress : nullptr, use,
                       converted_wide, &ex, threads);
  });
  release_free_memory();  // the other ranks' buffers, freed into their threads' heaps
}

}  // namespace

void share_tile_store(TileStore& store, const std::string& input, const SaliencyOptions& options, uint64_t memory_limit,
                      unsigned tiles, const std::function<void(const char*, double)>& progress, StoreUse use) {
  TileExchange* exchange = options.exchange;
  if (!exchange) return build_on_threads(store, input, options, memory_limit, tiles, progress, use);
  if (exchange->ranks() == 1) {
    lead_step(exchange, [&] { build_tile_store(store, input, options, memory_limit, tiles, progress, use); });
    return;
  }
  // Rank 0 puts the input in place and sees whether it reads in ranges; the files the ranks
  // write their ranges of exist before any opens them.
  int converted_wide = -1;
  bool ranged = false;
  lead_step(exchange, [&] { ranged = prepare_input(store, input, converted_wide, true); });
  TileBytes b;
  if (exchange->rank() == 0) {
    b.put(std::vector<uint8_t>(store.dir.path().begin(), store.dir.path().end()));
    b.put(std::vector<uint8_t>(store.input.begin(), store.input.end()));
    b.put(int32_t(converted_wide));
    b.put(uint8_t(ranged));
  }
  const auto said = tile_gather(exchange, b.data);  // (rank 0's: the only one not empty)
  if (exchange->rank() != 0) {
    TileBytesReader in{said[0]};
    const std::vector<uint8_t> dir = in.get_vector<uint8_t>(), path = in.get_vector<uint8_t>();
    store.dir.borrow(std::string(dir.begin(), dir.end()));
    store.input = std::string(path.begin(), path.end());
    converted_wide = in.get<int32_t>();
    ranged = in.get<uint8_t>() != 0;
  }
  if (ranged) {
    build_store_passes(store, input, options, memory_limit, tiles, progress, use, converted_wide, exchange, 1);
    return;
  }
  lead_step(exchange, [&] {
    build_store_passes(store, input, options, memory_limit, tiles, progress, use, converted_wide, nullptr, 1);
  });
  const auto all = tile_gather(exchange, exchange->rank() == 0 ? describe(store).data : std::vector<uint8_t>());
  if (exchange->rank() != 0) adopt(store, all[0], options);
}

}  // namespace meshsal
