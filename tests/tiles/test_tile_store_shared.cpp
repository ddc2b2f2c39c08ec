// The tile store built by every rank (share_tile_store, issue 41): each rank reads its share
// of a PLY that reads in ranges and buckets its share of the triangles; the store is the
// one a single process builds (its files to the byte, each tile's bucket the same faces,
// the same box, origin, counts, histogram and plan). Other inputs are built by rank 0 as
// before; a bad face in one rank's share stops every rank with its reason.
#include <zlib.h>

#include <algorithm>
#include <cstring>
#include <memory>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "cli/synthetic.h"
#include "cli_run.h"
#include "meshsal/meshsal.h"
#include "out_of_core_util.h"
#include "test_util.h"
#include "thread_exchange.h"
#include "io/ply_stream.h"
#include "tiles/tile_store.h"

using namespace meshsal;
using namespace meshsal_test;

namespace {

std::string file_of(const TileStore& s, const std::string& name) {
  std::ifstream in(s.dir.file(name), std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// Tile t's faces over every rank's bucket file, sorted by face number.
std::vector<TileFace> bucket_of(const TileStore& s, size_t t) {
  std::vector<TileFace> faces;
  store_tile_source(s).bucket(t, faces);
  std::sort(faces.begin(), faces.end(), [](const TileFace& a, const TileFace& b) { return a.face < b.face; });
  return faces;
}

bool same_faces(const std::vector<TileFace>& a, const std::vector<TileFace>& b) {
  if (a.size() != b.size()) return false;
  for (size_t i = 0; i < a.size(); ++i)
    if (a[i].face != b[i].face || !std::equal(a[i].c, a[i].c + 3, b[i].c)) return false;
  return true;
}

SaliencyOptions store_options(TileExchange* ex, unsigned threads = 1) {
  SaliencyOptions o = cpu(Method::Fast);
  o.exchange = ex;
  o.threads = threads;
  return o;
}

// What each of `ranks` ranks (in threads) throws building a store of `path` ("" for none).
std::vector<std::string> rank_errors(int ranks, const std::string& path, const std::filesystem::path& dir) {
  std::vector<std::string> said(static_cast<size_t>(ranks));
  run_ranks(ranks, [&](ThreadExchange& ex) {
    TileStore s(dir.string());
    try {
      share_tile_store(s, path, store_options(&ex), 0, 2, {});
    } catch (const Error& e) {
      said[size_t(ex.rank())] = e.what();
    }
  });
  return said;
}

}  // namespace

TEST_CASE("tile store built by every rank is the one-process store", "[tiles][outofcore][shared]") {
  const auto dir = scratch_dir("store_shared");
  Mesh mesh = make_bumpy_sphere(5);
  // An unreferenced vertex in the middle of the list, so a rank's vertices are not all points.
  mesh.positions.insert(mesh.positions.begin() + 3 * 5000, {0.1f, 0.2f, 0.3f});
  for (uint32_t& v : mesh.triangles)
    if (v >= 5000) ++v;
  const std::string in = (dir / "in.ply").string();
  write_ply(in, mesh, {});
  const uint64_t limit = uint64_t(1) << 30;
  TileStore one(dir.string());
  share_tile_store(one, in, store_options(nullptr), limit, 3, {});  // one thread: read front to back
  REQUIRE(tile_count(one.plan) > 1);
  REQUIRE(one.bucket_ranks == 1);
  // One process on three threads: ranks in threads of its own, rank 0's store the result.
  TileStore threaded(dir.string());
  share_tile_store(threaded, in, store_options(nullptr, 3), limit, 3, {});
  CHECK(threaded.readers == 3);       // the ranks in threads read the input, each its share
  CHECK(threaded.bucket_ranks == 1);  // (rank 0 buckets every triangle)
  CHECK(threaded.plan.threads == 3);
  CHECK(one.readers == 1);
  CHECK(threaded.histogram.count == one.histogram.count);
  for (const char* name : {"xyz", "tri.u32", "pos.f32"}) CHECK(file_of(threaded, name) == file_of(one, name));
  for (size_t t = 0; t < tile_count(one.plan); ++t) CHECK(same_faces(bucket_of(threaded, t), bucket_of(one, t)));
  for (int ranks : {2, 3}) {
    INFO(ranks << " ranks");
    std::vector<std::unique_ptr<TileStore>> stores;
    for (int r = 0; r < ranks; ++r) stores.push_back(std::make_unique<TileStore>(dir.string()));
    run_ranks(ranks, [&](ThreadExchange& ex) {
      share_tile_store(*stores[size_t(ex.rank())], in, store_options(&ex), limit, 3, {});
    });
    for (int r = 0; r < ranks; ++r) {
      const TileStore& s = *stores[size_t(r)];
      INFO("rank " << r);
      CHECK(s.dir.path() == stores[0]->dir.path());  // the one folder they all reach
      CHECK(s.bucket_ranks == ranks);                // every rank bucketed its share
      CHECK(s.readers == ranks);                     // and read its share
      CHECK(s.vertices == one.vertices);
      CHECK(s.triangles == one.triangles);
      CHECK(s.points == one.points);
      CHECK(s.points == mesh.vertex_count() - 1);
      for (int a = 0; a < 3; ++a) {
        CHECK(s.origin[a] == one.origin[a]);
        CHECK(s.box.min[a] == one.box.min[a]);
        CHECK(s.box.max[a] == one.box.max[a]);
        CHECK(s.plan.tiles[a] == one.plan.tiles[a]);
      }
      CHECK(s.plan.tile_edge == one.plan.tile_edge);
      CHECK(s.largest_tile_estimate == one.largest_tile_estimate);
      CHECK(s.double_positions == one.double_positions);
      CHECK(s.xyz_float == one.xyz_float);
    }
    const TileStore& s = *stores[0];
    CHECK(s.histogram.count == one.histogram.count);  // rank 0's: every rank's bins added
    for (const char* name : {"xyz", "tri.u32", "pos.f32"}) {
      INFO(name);
      CHECK(file_of(s, name) == file_of(one, name));
    }
    for (size_t t = 0; t < tile_count(one.plan); ++t) {
      INFO("tile " << t);
      CHECK(same_faces(bucket_of(s, t), bucket_of(one, t)));
    }
  }
}

TEST_CASE("tile store under ranks: other inputs built by rank 0, a bad face stops every rank", "[tiles][outofcore][shared]") {
  const auto dir = scratch_dir("store_shared_inputs");
  const Mesh mesh = make_bumpy_sphere(3);
  const std::string plain = (dir / "in.ply").string();
  write_ply(plain, mesh, {});
  std::string bytes;
  {
    std::ifstream f(plain, std::ios::binary);
    bytes.assign(std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>());
  }
  // gzip: read front to back by rank 0 alone; the same store.
  const std::string gz = (dir / "in.ply.gz").string();
  {
    gzFile out = gzopen(gz.c_str(), "wb");
    REQUIRE(gzwrite(out, bytes.data(), unsigned(bytes.size())) == int(bytes.size()));
    gzclose(out);
  }
  TileStore one(dir.string());
  share_tile_store(one, plain, store_options(nullptr), 0, 2, {});
  std::vector<std::unique_ptr<TileStore>> stores;
  for (int r = 0; r < 2; ++r) stores.push_back(std::make_unique<TileStore>(dir.string()));
  run_ranks(2, [&](ThreadExchange& ex) { share_tile_store(*stores[size_t(ex.rank())], gz, store_options(&ex), 0, 2, {}); });
  for (const auto& s : stores) {
    CHECK(s->bucket_ranks == 1);
    CHECK(s->readers == 1);
    CHECK(s->points == one.points);
    CHECK(file_of(*s, "pos.f32") == file_of(one, "pos.f32"));
  }
  // A face in the last rank's share names a vertex the file lacks: every rank throws that.
  std::string bad = bytes;
  const size_t last_face = bad.size() - 13;
  const int32_t out_of_range = 1 << 30;
  std::memcpy(&bad[last_face + 1], &out_of_range, 4);
  const std::string bad_path = (dir / "bad.ply").string();
  std::ofstream(bad_path, std::ios::binary) << bad;
  const std::vector<std::string> said = rank_errors(3, bad_path, dir);
  for (const std::string& m : said) {
    INFO(m);
    CHECK(m.find("uses vertex 1073741824") != std::string::npos);
    CHECK(m == said[2]);
  }
}

TEST_CASE("tile store: faces whose bytes add up to triangles' but are not triangles are refused", "[tiles][outofcore][shared]") {
  // Every face is 1 + 4n bytes: faces that add up to 13 bytes each while one is no triangle
  // need one of fewer than 3 corners, which no reader takes. Here a quad and a 2-gon: the
  // file reads in ranges by its size, and both the one reader and the ranks refuse it.
  const auto dir = scratch_dir("store_fake_triangles");
  std::string body;
  auto put_f = [&](float x) { body.append(reinterpret_cast<const char*>(&x), 4); };
  auto put_i = [&](int32_t x) { body.append(reinterpret_cast<const char*>(&x), 4); };
  for (int v = 0; v < 4; ++v) put_f(float(v & 1)), put_f(float(v >> 1)), put_f(0);
  body.push_back(4);
  for (int32_t v : {0, 1, 3, 2}) put_i(v);
  body.push_back(2);
  for (int32_t v : {0, 1}) put_i(v);
  const std::string path = (dir / "fake.ply").string();
  std::ofstream(path, std::ios::binary) << "ply\nformat binary_little_endian 1.0\nelement vertex 4\n"
                                           "property float x\nproperty float y\nproperty float z\nelement face 2\n"
                                           "property list uchar int vertex_indices\nend_header\n"
                                        << body;
  REQUIRE(PlyStream(path).ranged());
  TileStore one(dir.string());
  CHECK_THROWS_WITH(share_tile_store(one, path, store_options(nullptr), 0, 1, {}),
                    Catch::Contains("face with 2 vertices"));
  const std::vector<std::string> said = rank_errors(2, path, dir);
  for (const std::string& m : said) {
    INFO(m);
    CHECK(m.find("fake.ply") != std::string::npos);
    CHECK(m == said[0]);
  }
}
