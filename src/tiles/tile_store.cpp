#include "tiles/tile_store.h"

#include <sys/stat.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <exception>
#include <map>
#include <memory>

#include "core/memory_size.h"
#include "core/model_frame.h"
#include "core/parallel.h"
#include "core/release_memory.h"
#include "io/ply_stream.h"
#include "meshsal/meshsal.h"
#include "saliency/saliency.h"
#include "tiles/tile_bytes.h"
#include "tiles/tile_reduce.h"

namespace meshsal {

namespace {

constexpr size_t kChunk = 1 << 16;  // vertices or faces per read

// Tile t's bucket as rank r filled it (each rank buckets its share of the triangles).
std::string bucket_name(size_t t, int r) { return "bucket_" + std::to_string(t) + "_r" + std::to_string(r) + ".bin"; }

// A plan's estimates: the largest tile's peak in bytes and the work of all tiles (their
// points, halos included) per mesh point.
struct PlanCost {
  uint64_t largest = 0;
  double work = 0;
};

PlanCost plan_cost(const TilePlan& plan, const PointHistogram& h, uint64_t points) {
  PlanCost cost;
  const double reach = plan.query_margin + plan.source_margin + h.bin[0] + h.bin[1] + h.bin[2];
  // The constants hold for the default scales' 8 sigmas; each more costs a query point its
  // average and raw map (16 bytes) and, in the exact sweep (every sigma at once), a halo
  // point its average (8 bytes).
  const double more = std::max(0.0, double(filter_sigma_units(plan.scales).size()) - 8);
  const double own_bytes = kOwnBytesPerVertex + 16 * more;
  const double halo_bytes = plan.method == Method::Fast ? kFastHaloBytesPerVertex : kHaloBytesPerVertex + 8 * more;
  double total = 0;
  for (int z = 0; z < plan.tiles[2]; ++z)
    for (int y = 0; y < plan.tiles[1]; ++y)
      for (int x = 0; x < plan.tiles[0]; ++x) {
        BoundingBox b, own;
        const int c[3] = {x, y, z};
        for (int a = 0; a < 3; ++a) {
          own.min[a] = plan.box.min[a] + c[a] * plan.tile_edge;
          own.max[a] = plan.box.min[a] + (c[a] + 1) * plan.tile_edge;
          b.min[a] = own.min[a] - reach;
          b.max[a] = own.max[a] + reach;
        }
        const uint64_t mine = h.within(own);
        if (mine == 0) continue;  // tiles without points of their own do nothing
        const uint64_t n = std::max(h.within(b), mine);
        total += double(n);
        cost.largest = std::max(cost.largest, uint64_t(double(mine) * own_bytes + double(n - mine) * halo_bytes));
      }
  cost.work = points ? total / double(points) : 1;
  return cost;
}

BoundingBox empty_box() {
  BoundingBox b;
  for (int a = 0; a < 3; ++a) b.min[a] = INFINITY, b.max[a] = -INFINITY;
  return b;
}

}  // namespace

std::string mib_text(uint64_t bytes) { return std::to_string((bytes + (1 << 20) - 1) >> 20) + "M"; }

uint64_t PointHistogram::within(const BoundingBox& b) const {
  int lo[3], hi[3];
  for (int a = 0; a < 3; ++a) lo[a] = bin_of(b.min[a], a), hi[a] = bin_of(b.max[a], a);
  uint64_t sum = 0;
  for (int z = lo[2]; z <= hi[2]; ++z)
    for (int y = lo[1]; y <= hi[1]; ++y)
      for (int x = lo[0]; x <= hi[0]; ++x) sum += count[(size_t(z) * kBins + y) * kBins + x];
  return sum;
}

namespace {

using Progress = std::function<void(const char*, double)>;
// One bit per vertex: referenced by a face (a mesh point).
using PointBits = std::vector<uint64_t>;
bool is_point(const PointBits& bits, uint64_t v) { return (bits[v >> 6] >> (v & 63)) & 1; }

}  // namespace

void store_input(TileStore& store, const std::string& input_path, int& converted_wide) {
  struct stat st;
  if (::stat(input_path.c_str(), &st) != 0 || !S_ISREG(st.st_mode))
    throw Error(input_path + ": out of core reads regular files only (it reads the input more than once)");
  store.input = input_path;
  converted_wide = -1;  // a converted file's own precision (it is stored in double)
  if (PlyStream::readable(input_path)) return;
  Mesh m = load_mesh(input_path);
  converted_wide = positions_need_double(m) ? 1 : 0;
  m.double_positions = true;
  store.input = store.dir.file("input.ply");
  write_ply(store.input, m, {});
}

namespace {

// Every rank's part of the passes (one rank: all of it): vertex range [v0, v1) and triangle
// range [t0, t1), the reductions through the exchange.
struct Share {
  TileExchange* exchange = nullptr;
  int rank = 0, ranks = 1;
  unsigned parts = 1;  // the ranks that share this process's memory limit (ranks in threads)
  uint64_t v0 = 0, v1 = 0, t0 = 0, t1 = 0;
  void split(uint64_t vertices, uint64_t triangles) {
    v0 = vertices * uint64_t(rank) / uint64_t(ranks), v1 = vertices * uint64_t(rank + 1) / uint64_t(ranks);
    t0 = triangles * uint64_t(rank) / uint64_t(ranks), t1 = triangles * uint64_t(rank + 1) / uint64_t(ranks);
  }
};

// The vertices [first, first + count) of `buf` have finite coordinates (else the Error
// naming the first that has not).
void check_finite(const std::vector<double>& buf, size_t count, uint64_t first, const std::string& input_path) {
  for (size_t i = 0; i < 3 * count; ++i)
    if (!std::isfinite(buf[i]))
      throw Error(input_path + ": vertex " + std::to_string(first + i / 3) + " has a non-finite coordinate");
}

// Every rank's box joined (min of the minima, max of the maxima) and their counts summed.
void join_boxes(const Share& share, BoundingBox& box, uint64_t& count) {
  if (!share.exchange) return;
  TileBytes b;
  b.put(box);
  b.put(count);
  box = empty_box();
  count = 0;
  for (const auto& bytes : tile_gather(share.exchange, b.data)) {
    TileBytesReader in{bytes};
    const BoundingBox other = in.get<BoundingBox>();
    for (int a = 0; a < 3; ++a) box.min[a] = std::min(box.min[a], other.min[a]), box.max[a] = std::max(box.max[a], other.max[a]);
    count += in.get<uint64_t>();
  }
}

// Whether any rank's flag is set.
bool any_rank(const Share& share, bool mine) {
  if (!share.exchange) return mine;
  for (const auto& bytes : tile_gather(share.exchange, {uint8_t(mine)}))
    if (!bytes.empty() && bytes[0]) return true;
  return false;
}

// The coordinates as read into the xyz file: as floats where they fit (store.xyz_float).
void put_xyz(ScratchWriter& out, const TileStore& store, const double* xyz, size_t count, std::vector<float>& scratch) {
  if (!store.xyz_float) return out.write(xyz, 24 * count);
  scratch.resize(3 * count);
  for (size_t i = 0; i < 3 * count; ++i) scratch[i] = float(xyz[i]);
  out.write(scratch.data(), 12 * count);
}

// `count` vertices' coordinates from the xyz file (at its position), as doubles.
void get_xyz(ScratchReader& in, const TileStore& store, double* xyz, size_t count, std::vector<float>& scratch) {
  if (!store.xyz_float) return in.read_exact(xyz, 24 * count);
  scratch.resize(3 * count);
  in.read_exact(scratch.data(), 12 * count);
  for (size_t i = 0; i < 3 * count; ++i) xyz[i] = scratch[i];
}

// Pass A for one reader of the whole file (a gzip, polygons: read front to back): the
// coordinates as read to xyz, the triangles to tri.u32; returns the point bits.
PointBits read_input(TileStore& store, const std::string& input_path, int converted_wide, const Progress& report) {
  PlyStream ply(store.input);
  store.vertices = ply.vertex_count();
  store.double_positions = converted_wide >= 0 ? converted_wide == 1 : ply.double_positions();
  if (store.vertices == 0) throw Error(input_path + ": mesh has no vertices");
  PointBits referenced((store.vertices + 63) / 64, 0);
  store.xyz_float = ply.positions_fit_float();
  ScratchWriter xyz(store.dir.file("xyz"));
  std::vector<double> buf(3 * kChunk);
  std::vector<float> narrow;
  uint64_t v = 0;
  for (size_t got; (got = ply.read_vertices(buf.data(), kChunk)) > 0; v += got) {
    check_finite(buf, got, v, input_path);
    put_xyz(xyz, store, buf.data(), got, narrow);
  }
  xyz.close();
  ScratchWriter tri(store.dir.file("tri.u32"));
  std::vector<uint32_t> t;
  uint64_t faces_read = 0;
  for (size_t got; (got = ply.read_faces(t, kChunk)) > 0;) {
    faces_read += got;
    for (uint32_t v : t) referenced[v >> 6] |= uint64_t(1) << (v & 63);
    store.triangles += t.size() / 3;
    tri.write_vector(t);
    t.clear();
    report("reading", double(faces_read) / double(std::max<uint64_t>(1, ply.face_count())));
  }
  tri.close();
  if (store.triangles == 0) throw Error(input_path + ": mesh has no faces");
  if (store.triangles > UINT32_MAX) throw Error(input_path + ": more than 4294967295 triangles");
  return referenced;
}

// Pass A of one rank of several over a file read in ranges (PlyStream::ranged: a face is a
// triangle): its vertices into its range of xyz, its faces into its range of tri.u32;
// then the point bits of its vertices, every rank's faces' corners joined (each rank's bits
// through a file of their own). The files exist (rank 0 made them).
PointBits read_input_range(TileStore& store, const std::string& input_path, int converted_wide, Share& share,
                           const Progress& report) {
  std::unique_ptr<PlyStream> opened;  // (opened on every rank: one that cannot must not strand the others)
  all_step(share.exchange, [&] {
    opened = std::make_unique<PlyStream>(store.input);
    store.vertices = opened->vertex_count();
    store.triangles = opened->face_count();
    if (store.vertices == 0) throw Error(input_path + ": mesh has no vertices");
    if (store.triangles == 0) throw Error(input_path + ": mesh has no faces");
    if (store.triangles > UINT32_MAX) throw Error(input_path + ": more than 4294967295 triangles");
  });
  PlyStream& ply = *opened;
  share.split(store.vertices, store.triangles);
  store.xyz_float = ply.positions_fit_float();
  store.double_positions = converted_wide >= 0 ? converted_wide == 1 : ply.double_positions();
  PointBits referenced((store.vertices + 63) / 64, 0);
  all_step(share.exchange, [&] {
    ply.seek_vertex(share.v0);
    ScratchWriter xyz(store.dir.file("xyz"), share.v0 * store.xyz_bytes());
    std::vector<double> buf(3 * kChunk);
    std::vector<float> narrow;
    for (uint64_t v = share.v0; v < share.v1;) {
      const size_t got = ply.read_vertices(buf.data(), size_t(std::min<uint64_t>(kChunk, share.v1 - v)));
      if (got == 0) throw Error("internal: a vertex range ends early");
      check_finite(buf, got, v, input_path);
      put_xyz(xyz, store, buf.data(), got, narrow);
      v += got;
    }
    xyz.close();
    ply.seek_face(share.t0);
    ScratchWriter tri(store.dir.file("tri.u32"), share.t0 * 12);
    std::vector<uint32_t> t;
    for (uint64_t f = share.t0; f < share.t1;) {
      t.clear();
      const size_t got = ply.read_faces(t, size_t(std::min<uint64_t>(kChunk, share.t1 - f)));
      if (got == 0) throw Error("internal: a face range ends early");
      if (t.size() != 3 * got)  // the file's size matched triangles' alone, but a face is not one
        throw Error(input_path + ": a face among faces " + std::to_string(f) + ".." + std::to_string(f + got - 1) +
                    " is not a triangle, where the file's size says every face is");
      for (uint32_t v : t) referenced[v >> 6] |= uint64_t(1) << (v & 63);
      tri.write_vector(t);
      f += got;
      report("reading", double(f - share.t0) / double(std::max<uint64_t>(1, share.t1 - share.t0)));
    }
    tri.close();
    // This rank's corner bits for the others; every rank's for this one's vertices below.
    ScratchWriter bits(store.dir.file("points_r" + std::to_string(share.rank) + ".bits"));
    bits.write_vector(referenced);
    bits.close();
  });
  all_step(share.exchange, [&] {
    const uint64_t w0 = share.v0 / 64, w1 = (share.v1 + 63) / 64;
    std::fill(referenced.begin(), referenced.end(), 0);
    std::vector<uint64_t> words(size_t(w1 - w0));
    for (int r = 0; r < share.ranks; ++r) {
      ScratchReader in(store.dir.file("points_r" + std::to_string(r) + ".bits"));
      in.seek(w0 * 8);
      in.read_exact(words.data(), words.size() * 8);
      for (size_t i = 0; i < words.size(); ++i) referenced[size_t(w0) + i] |= words[i];
    }
  });
  return referenced;
}

// Pass B over this rank's vertices: the origin (set_model_positions' rule, over every
// rank's points), local floats to pos.f32, their box and the point count (every rank's),
// and the histogram of the points (rank 0's, every rank's counts added).
void local_positions(TileStore& store, const PointBits& points, const Share& share) {
  const uint64_t v0 = share.v0, v1 = share.v1;
  BoundingBox model = empty_box();
  all_step(share.exchange, [&] {
    ScratchReader xyz(store.dir.file("xyz"));
    xyz.seek(v0 * store.xyz_bytes());
    std::vector<double> buf(3 * kChunk);
    std::vector<float> narrow;
    for (uint64_t v = v0; v < v1;) {
      const size_t got = size_t(std::min<uint64_t>(kChunk, v1 - v));
      get_xyz(xyz, store, buf.data(), got, narrow);
      for (size_t i = 0; i < got; ++i)
        if (is_point(points, v + i))
          for (int a = 0; a < 3; ++a) {
            model.min[a] = std::min(model.min[a], buf[3 * i + a]);
            model.max[a] = std::max(model.max[a], buf[3 * i + a]);
          }
      v += got;
    }
  });
  uint64_t unused = 0;
  join_boxes(share, model, unused);
  for (int a = 0; a < 3; ++a) store.origin[a] = model.min[a] / 2 + model.max[a] / 2;
  BoundingBox box = empty_box();
  uint64_t count = 0;
  all_step(share.exchange, [&] {
    ScratchReader xyz(store.dir.file("xyz"));
    xyz.seek(v0 * store.xyz_bytes());
    ScratchWriter pos(store.dir.file("pos.f32"), v0 * 12);
    std::vector<double> buf(3 * kChunk);
    std::vector<float> local(3 * kChunk), narrow;
    for (uint64_t v = v0; v < v1;) {
      const size_t got = size_t(std::min<uint64_t>(kChunk, v1 - v));
      get_xyz(xyz, store, buf.data(), got, narrow);
      for (size_t i = 0; i < 3 * got; ++i) local[i] = local_coordinate(buf[i], store.origin[i % 3]);
      for (size_t i = 0; i < got; ++i)
        if (is_point(points, v + i)) {
          count++;
          for (int a = 0; a < 3; ++a) {
            box.min[a] = std::min(box.min[a], double(local[3 * i + a]));
            box.max[a] = std::max(box.max[a], double(local[3 * i + a]));
          }
        }
      pos.write(local.data(), 3 * got * sizeof(float));
      v += got;
    }
    pos.close();
  });
  join_boxes(share, box, count);
  store.box = box;
  store.points = count;
  PointHistogram& hist = store.histogram;
  hist.box = box;
  for (int a = 0; a < 3; ++a) hist.bin[a] = std::max((box.max[a] - box.min[a]) / PointHistogram::kBins, 1e-30);
  all_step(share.exchange, [&] {
    ScratchReader pos(store.dir.file("pos.f32"));
    pos.seek(v0 * 12);
    std::vector<float> buf(3 * kChunk);
    for (uint64_t v = v0; v < v1;) {
      const size_t got = size_t(std::min<uint64_t>(kChunk, v1 - v));
      pos.read_exact(buf.data(), got * 12);
      for (size_t i = 0; i < got; ++i)
        if (is_point(points, v + i)) hist.add(&buf[3 * i]);
      v += got;
    }
  });
  if (!share.exchange) return;
  // Rank 0 adds the others' bins (sent as the occupied ones: a surface fills few).
  TileBytes b;
  if (share.rank != 0)
    for (size_t i = 0; i < hist.count.size(); ++i)
      if (hist.count[i]) b.put(uint32_t(i)), b.put(hist.count[i]);
  const auto all = share.exchange->gather(b.data, 0);
  for (size_t r = 1; r < all.size(); ++r)
    for (TileBytesReader in{all[r]}; !in.done();) {
      const uint32_t i = in.get<uint32_t>();
      const uint32_t c = in.get<uint32_t>();
      if (i >= hist.count.size()) throw Error("tiled saliency: a rank sent a histogram bin out of range");
      hist.count[i] += c;
    }
}

// The tile count: the fewest (at least min_tiles) whose largest tile fits the limit,
// among those whose halos cost at most kMaxTileWork times the untiled work (smaller
// tiles would shrink little: the halo, the filter's reach, stays).
void choose_tiling(TileStore& store, const std::string& input_path, const SaliencyOptions& options,
                   uint64_t memory_limit, unsigned min_tiles) {
  unsigned tiles = std::max(1u, min_tiles);
  store.plan = make_tile_plan(store.box, store.points, options, tiles);
  PlanCost cost = plan_cost(store.plan, store.histogram, store.points);
  if (memory_limit) {
    uint64_t best = cost.largest;
    while (kBaseBytes + cost.largest > memory_limit) {
      const unsigned next = std::min(kMaxTiles, tiles + std::max(1u, tiles / 4));
      const TilePlan finer = make_tile_plan(store.box, store.points, options, next);
      const PlanCost finer_cost = plan_cost(finer, store.histogram, store.points);
      if (next == tiles || finer_cost.work > kMaxTileWork) break;
      tiles = next;
      store.plan = finer;
      cost = finer_cost;
      best = std::min(best, cost.largest);
    }
    if (kBaseBytes + cost.largest > memory_limit)
      throw Error("memory limit " + memory_size_text(memory_limit) + " is too small for " + input_path +
                  ": the smallest tile with its halo (the filter's reach around it) needs about " +
                  mib_text(best) + "; the smallest workable limit is about " + mib_text(kBaseBytes + best));
  }
  store.largest_tile_estimate = cost.largest;
}

// Whether triangle c, all of whose corners are in the block at `first`, has an area
// (validate_mesh's test).
bool has_area(const uint32_t* c, const std::vector<float>& pos, uint64_t first) {
  double u[3], w[3];
  for (int a = 0; a < 3; ++a) {
    u[a] = double(pos[3 * (c[1] - first) + a]) - pos[3 * (c[0] - first) + a];
    w[a] = double(pos[3 * (c[2] - first) + a]) - pos[3 * (c[0] - first) + a];
  }
  return u[1] * w[2] - u[2] * w[1] != 0 || u[2] * w[0] - u[0] * w[2] != 0 || u[0] * w[1] - u[1] * w[0] != 0;
}

// Pass C over this rank's triangles: each to the bucket of every tile one of its corners
// lies in (this rank's file of that bucket), a block of vertex positions at a time.
void fill_buckets(TileStore& store, const std::string& input_path, uint64_t memory_limit, const Share& share,
                  const Progress& report) {
  const size_t ntiles = tile_count(store.plan);
  std::vector<std::vector<TileFace>> pending(ntiles);
  size_t pending_count = 0;
  const uint64_t part = memory_limit / share.parts;  // (the buffers of ranks in threads share the limit)
  const size_t flush_at = std::max<size_t>(kChunk, memory_limit ? size_t(part / 8 / sizeof(TileFace)) : (1u << 22) / share.parts);
  auto flush = [&]() {
    for (size_t t = 0; t < ntiles; ++t) {
      if (pending[t].empty()) continue;
      ScratchWriter out(store.dir.file(bucket_name(t, share.rank)), true);
      out.write_vector(pending[t]);
      out.close();
      std::vector<TileFace>().swap(pending[t]);
    }
    pending_count = 0;
  };
  bool any_area = false;  // validate_mesh's test, on triangles within one block
  all_step(share.exchange, [&] {
    const uint64_t mine = std::max<uint64_t>(1, share.t1 - share.t0);
    for (uint64_t first = 0; first < store.vertices; first += store.block) {
      const size_t count = size_t(std::min<uint64_t>(store.block, store.vertices - first));
      std::vector<float> pos(3 * count);
      {
        ScratchReader in(store.dir.file("pos.f32"));
        in.seek(first * 12);
        in.read_exact(pos.data(), pos.size() * sizeof(float));
      }
      auto in_block = [&](uint32_t v) { return v >= first && v < first + count; };
      ScratchReader tri(store.dir.file("tri.u32"));
      tri.seek(share.t0 * 12);
      std::vector<uint32_t> buf(3 * kChunk);
      std::vector<size_t> tile(3 * kChunk);  // each corner's tile (SIZE_MAX: outside the block)
      for (uint64_t f = share.t0; f < share.t1;) {
        const size_t got = size_t(std::min<uint64_t>(kChunk, share.t1 - f));
        tri.read_exact(buf.data(), got * 12);
        parallel_for(3 * got, store.plan.threads, 1 << 14, [&](size_t begin, size_t end) {
          for (size_t i = begin; i < end; ++i)
            tile[i] = in_block(buf[i]) ? tile_of(store.plan, &pos[3 * (buf[i] - first)]) : SIZE_MAX;
        });
        for (size_t i = 0; i < got; ++i, ++f) {
          const uint32_t* c = &buf[3 * i];
          if (!any_area && in_block(c[0]) && in_block(c[1]) && in_block(c[2])) any_area = has_area(c, pos, first);
          size_t seen[3];
          int nseen = 0;
          for (int k = 0; k < 3; ++k) {
            const size_t t = tile[3 * i + k];
            if (t == SIZE_MAX) continue;
            if (std::find(seen, seen + nseen, t) != seen + nseen) continue;
            seen[nseen++] = t;
            pending[t].push_back({uint32_t(f), {c[0], c[1], c[2]}});
            pending_count++;
          }
        }
        if (pending_count >= flush_at) flush();
        report("tiling", (double(first) + double(f - share.t0) / double(mine) * double(count)) / double(store.vertices));
      }
    }
    flush();
  });
  if (!any_rank(share, any_area) && store.block >= store.vertices)
    throw Error(input_path + ": every triangle has zero area (degenerate mesh)");
}

// The passes after the input is in place (store.input): one rank's (the whole file read
// front to back, without an exchange) or every rank's share of a file read in ranges.
void build_passes(TileStore& store, const std::string& input_path, const SaliencyOptions& options,
                  uint64_t memory_limit, unsigned min_tiles, const Progress& report, StoreUse use,
                  int converted_wide, Share share) {
  const bool ranged = share.exchange != nullptr;
  // Pass C holds a block of vertices (12 bytes each as floats) in a quarter of the limit.
  store.block = memory_limit ? std::max<size_t>(kChunk, size_t((memory_limit / 4) / 16)) : SIZE_MAX;
  // Ranks in threads leave pass C to rank 0 (below): one block, buckets in face order.
  store.bucket_ranks = share.parts > 1 ? 1 : share.ranks;
  store.readers = ranged ? share.ranks : 1;
  if (!share.exchange) ScratchWriter(store.dir.file("pos.f32")).close();  // (the ranks' own is made first)
  {
    PointBits points;
    if (ranged) {
      points = read_input_range(store, input_path, converted_wide, share, report);
    } else {
      points = read_input(store, input_path, converted_wide, report);
      share.split(store.vertices, store.triangles);
    }
    local_positions(store, points, share);
  }
  if (use == StoreUse::FilesOnly) {
    store.plan = make_tile_plan(store.box, store.points, options, std::max(1u, min_tiles));
    return;
  }
  // Rank 0 picks the tiling from its histogram (the whole mesh's); the others take its plan.
  const bool lead = share.rank == 0;
  if (share.exchange) {
    lead_step(share.exchange, [&] { choose_tiling(store, input_path, options, memory_limit, min_tiles); });
    TileBytes b;
    if (lead) {
      b.put(store.largest_tile_estimate);
      b.put(store.plan.tile_edge);
      for (int a = 0; a < 3; ++a) b.put(store.plan.tiles[a]);
    }
    const auto said = tile_gather(share.exchange, b.data);
    TileBytesReader in{said[0]};
    if (!lead) {
      store.largest_tile_estimate = in.get<uint64_t>();
      store.plan = make_tile_plan(store.box, store.points, options, 1);
      store.plan.tile_edge = in.get<double>();
      for (int a = 0; a < 3; ++a) store.plan.tiles[a] = in.get<int>();
    }
  } else {
    choose_tiling(store, input_path, options, memory_limit, min_tiles);
  }
  if (share.parts == 1) return fill_buckets(store, input_path, memory_limit, share, report);
  // Ranks in threads: rank 0 alone buckets every triangle, on every thread (one block where
  // one holds every vertex, so each bucket is in face order, each face once: ranks' shares
  // would leave a tile's bucket in runs to merge, and a vertex block each).
  Share alone;
  alone.t1 = store.triangles;
  release_free_memory();  // the passes' buffers, freed into each rank's thread's heap
  lead_step(share.exchange, [&] { fill_buckets(store, input_path, memory_limit, alone, report); });
}

}  // namespace

void build_store_passes(TileStore& store, const std::string& input_path, const SaliencyOptions& options,
                        uint64_t memory_limit, unsigned min_tiles,
                        const std::function<void(const char*, double)>& progress, StoreUse use, int converted_wide,
                        TileExchange* exchange, unsigned memory_parts) {
  const Progress report = [&](const char* stage, double f) {
    if (progress) progress(stage, f);
  };
  Share share;
  if (exchange) share.exchange = exchange, share.rank = exchange->rank(), share.ranks = exchange->ranks();
  share.parts = std::max(1u, memory_parts);
  build_passes(store, input_path, options, memory_limit, min_tiles, report, use, converted_wide, share);
}

void build_tile_store(TileStore& store, const std::string& input_path, const SaliencyOptions& options,
                      uint64_t memory_limit, unsigned min_tiles,
                      const std::function<void(const char*, double)>& progress, StoreUse use) {
  int converted_wide = -1;
  store_input(store, input_path, converted_wide);
  build_store_passes(store, input_path, options, memory_limit, min_tiles, progress, use, converted_wide, nullptr, 1);
}

TileSource store_tile_source(const TileStore& store) {
  TileSource source;
  source.bucket = [&store](size_t u, std::vector<TileFace>& into) {
    // Every rank's file of it in rank order: each rank's faces are later ones than the last's.
    for (int r = 0; r < store.bucket_ranks; ++r) {
      const std::string path = store.dir.file(bucket_name(u, r));
      struct stat st;
      if (::stat(path.c_str(), &st) != 0) continue;  // no triangle there
      append_scratch_records(path, into);
    }
  };
  source.positions = [&store](const std::vector<uint32_t>& sorted, std::vector<float>& xyz) {
    xyz.resize(3 * sorted.size());
    read_records(store.dir.file("pos.f32"), 12, sorted, xyz.data(), store.plan.threads);
  };
  return source;
}

void read_source_positions(const TileStore& store, uint64_t first, size_t count, double* out) {
  ScratchReader in(store.dir.file("xyz"));
  in.seek(first * store.xyz_bytes());
  std::vector<float> narrow;
  get_xyz(in, store, out, count, narrow);
}

void read_triangles(const TileStore& store, uint64_t first, size_t count, uint32_t* out) {
  ScratchReader in(store.dir.file("tri.u32"));
  in.seek(first * 12);
  in.read_exact(out, count * 12);
}

}  // namespace meshsal
