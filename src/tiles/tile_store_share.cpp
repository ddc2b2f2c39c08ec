// share_tile_store (tile_store.h): every rank builds its share of the store from an input
// that reads in ranges; otherwise rank 0 builds it and the others adopt its description.
#include <string>
#include <vector>

#include "io/ply_stream.h"
#include "tiles/tile_bytes.h"
#include "tiles/tile_reduce.h"
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
}

}  // namespace

void share_tile_store(TileStore& store, const std::string& input, const SaliencyOptions& options, uint64_t memory_limit,
                      unsigned tiles, const std::function<void(const char*, double)>& progress, StoreUse use) {
  TileExchange* exchange = options.exchange;
  if (!exchange || exchange->ranks() == 1) {
    lead_step(exchange, [&] { build_tile_store(store, input, options, memory_limit, tiles, progress, use); });
    return;
  }
  // Rank 0 puts the input in place and sees whether it reads in ranges; the files the ranks
  // write their ranges of exist before any opens them.
  int converted_wide = -1;
  bool ranged = false;
  lead_step(exchange, [&] {
    store_input(store, input, converted_wide);
    ranged = PlyStream(store.input).ranged();
    for (const char* name : {"xyz.f64", "tri.u32", "pos.f32"}) ScratchWriter(store.dir.file(name)).close();
  });
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
    build_store_passes(store, input, options, memory_limit, tiles, progress, use, converted_wide, exchange);
    return;
  }
  lead_step(exchange, [&] {
    build_store_passes(store, input, options, memory_limit, tiles, progress, use, converted_wide, nullptr);
  });
  const auto all = tile_gather(exchange, exchange->rank() == 0 ? describe(store).data : std::vector<uint8_t>());
  if (exchange->rank() != 0) adopt(store, all[0], options);
}

}  // namespace meshsal
