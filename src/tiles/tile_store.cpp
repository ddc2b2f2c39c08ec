#include "tiles/tile_store.h"

#include <sys/stat.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>

#include "core/memory_size.h"
#include "core/model_frame.h"
#include "core/parallel.h"
#include "io/ply_stream.h"
#include "meshsal/meshsal.h"
#include "saliency/saliency.h"

namespace meshsal {

namespace {

constexpr size_t kChunk = 1 << 16;  // vertices or faces per read

std::string bucket_name(size_t t) { return "bucket_" + std::to_string(t) + ".bin"; }

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

// The input as a binary PLY the passes can stream: itself, or another format converted
// once (this one step holds the mesh whole), in double so the coordinates stay the values
// as read. Sets store.input and store.double_positions's source.
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

// Pass A: the doubles as read to xyz.f64, the triangles to tri.u32; returns the point bits.
PointBits read_input(TileStore& store, const std::string& input_path, int converted_wide, const Progress& report) {
  PlyStream ply(store.input);
  store.vertices = ply.vertex_count();
  store.double_positions = converted_wide >= 0 ? converted_wide == 1 : ply.double_positions();
  if (store.vertices == 0) throw Error(input_path + ": mesh has no vertices");
  PointBits referenced((store.vertices + 63) / 64, 0);
  ScratchWriter xyz(store.dir.file("xyz.f64"));
  std::vector<double> buf(3 * kChunk);
  uint64_t v = 0;
  for (size_t got; (got = ply.read_vertices(buf.data(), kChunk)) > 0; v += got) {
    for (size_t i = 0; i < 3 * got; ++i)
      if (!std::isfinite(buf[i]))
        throw Error(input_path + ": vertex " + std::to_string(v + i / 3) + " has a non-finite coordinate");
    xyz.write(buf.data(), 3 * got * sizeof(double));
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

// Pass B: the origin (set_model_positions' rule), local floats to pos.f32, their box, the
// point count and the histogram of the points.
void local_positions(TileStore& store, const PointBits& points) {
  BoundingBox model = empty_box();
  {
    ScratchReader xyz(store.dir.file("xyz.f64"));
    std::vector<double> buf(3 * kChunk);
    uint64_t v = 0;
    for (size_t got; (got = xyz.read(buf.data(), buf.size() * sizeof(double)) / 24) > 0; v += got)
      for (size_t i = 0; i < got; ++i)
        if (is_point(points, v + i))
          for (int a = 0; a < 3; ++a) {
            model.min[a] = std::min(model.min[a], buf[3 * i + a]);
            model.max[a] = std::max(model.max[a], buf[3 * i + a]);
          }
  }
  for (int a = 0; a < 3; ++a) store.origin[a] = model.min[a] / 2 + model.max[a] / 2;
  BoundingBox box = empty_box();
  {
    ScratchReader xyz(store.dir.file("xyz.f64"));
    ScratchWriter pos(store.dir.file("pos.f32"));
    std::vector<double> buf(3 * kChunk);
    std::vector<float> local(3 * kChunk);
    uint64_t v = 0;
    for (size_t got; (got = xyz.read(buf.data(), buf.size() * sizeof(double)) / 24) > 0; v += got) {
      for (size_t i = 0; i < 3 * got; ++i) local[i] = local_coordinate(buf[i], store.origin[i % 3]);
      for (size_t i = 0; i < got; ++i)
        if (is_point(points, v + i)) {
          store.points++;
          for (int a = 0; a < 3; ++a) {
            box.min[a] = std::min(box.min[a], double(local[3 * i + a]));
            box.max[a] = std::max(box.max[a], double(local[3 * i + a]));
          }
        }
      pos.write(local.data(), 3 * got * sizeof(float));
    }
    pos.close();
  }
  store.box = box;
  PointHistogram& hist = store.histogram;
  hist.box = box;
  for (int a = 0; a < 3; ++a) hist.bin[a] = std::max((box.max[a] - box.min[a]) / PointHistogram::kBins, 1e-30);
  ScratchReader pos(store.dir.file("pos.f32"));
  std::vector<float> buf(3 * kChunk);
  uint64_t v = 0;
  for (size_t got; (got = pos.read(buf.data(), buf.size() * sizeof(float)) / 12) > 0; v += got)
    for (size_t i = 0; i < got; ++i)
      if (is_point(points, v + i)) hist.add(&buf[3 * i]);
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

// Pass C: each triangle to the bucket of every tile one of its corners lies in, a block of
// vertex positions at a time.
void fill_buckets(TileStore& store, const std::string& input_path, uint64_t memory_limit, const Progress& report) {
  const size_t ntiles = tile_count(store.plan);
  std::vector<std::vector<TileFace>> pending(ntiles);
  size_t pending_count = 0;
  const size_t flush_at = std::max<size_t>(kChunk, memory_limit ? size_t(memory_limit / 8 / sizeof(TileFace)) : (1u << 22));
  auto flush = [&]() {
    for (size_t t = 0; t < ntiles; ++t) {
      if (pending[t].empty()) continue;
      ScratchWriter out(store.dir.file(bucket_name(t)), true);
      out.write_vector(pending[t]);
      out.close();
      std::vector<TileFace>().swap(pending[t]);
    }
    pending_count = 0;
  };
  bool any_area = false;  // validate_mesh's test, on triangles within one block
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
    std::vector<uint32_t> buf(3 * kChunk);
    std::vector<size_t> tile(3 * kChunk);  // each corner's tile (SIZE_MAX: outside the block)
    uint32_t f = 0;
    for (size_t got; (got = tri.read(buf.data(), buf.size() * 4) / 12) > 0;) {
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
          pending[t].push_back({f, {c[0], c[1], c[2]}});
          pending_count++;
        }
      }
      if (pending_count >= flush_at) flush();
      report("tiling", (double(first) + double(f) / double(store.triangles) * double(count)) / double(store.vertices));
    }
  }
  flush();
  if (!any_area && store.block >= store.vertices)
    throw Error(input_path + ": every triangle has zero area (degenerate mesh)");
}

}  // namespace

void build_tile_store(TileStore& store, const std::string& input_path, const SaliencyOptions& options,
                      uint64_t memory_limit, unsigned min_tiles,
                      const std::function<void(const char*, double)>& progress, StoreUse use) {
  const Progress report = [&](const char* stage, double f) {
    if (progress) progress(stage, f);
  };
  int converted_wide = -1;
  store_input(store, input_path, converted_wide);
  // The passes hold a block of vertices (12 bytes each as floats) in a quarter of the limit.
  store.block = memory_limit ? std::max<size_t>(kChunk, size_t((memory_limit / 4) / 16)) : SIZE_MAX;
  {
    const PointBits points = read_input(store, input_path, converted_wide, report);
    local_positions(store, points);
  }
  if (use == StoreUse::FilesOnly) {
    store.plan = make_tile_plan(store.box, store.points, options, std::max(1u, min_tiles));
    return;
  }
  choose_tiling(store, input_path, options, memory_limit, min_tiles);
  fill_buckets(store, input_path, memory_limit, report);
}

TileSource store_tile_source(const TileStore& store) {
  TileSource source;
  source.bucket = [&store](size_t u, std::vector<TileFace>& into) {
    const std::string path = store.dir.file(bucket_name(u));
    struct stat st;
    if (::stat(path.c_str(), &st) != 0) return;  // no triangle there
    const std::vector<uint8_t> bytes = read_scratch_file(path);
    const size_t n = bytes.size() / sizeof(TileFace), at = into.size();
    into.resize(at + n);
    std::memcpy(into.data() + at, bytes.data(), n * sizeof(TileFace));
  };
  source.positions = [&store](const std::vector<uint32_t>& sorted, std::vector<float>& xyz) {
    xyz.resize(3 * sorted.size());
    read_records(store.dir.file("pos.f32"), 12, sorted, xyz.data());
  };
  return source;
}

void read_source_positions(const TileStore& store, uint64_t first, size_t count, double* out) {
  ScratchReader in(store.dir.file("xyz.f64"));
  in.seek(first * 24);
  in.read_exact(out, count * 24);
}

void read_triangles(const TileStore& store, uint64_t first, size_t count, uint32_t* out) {
  ScratchReader in(store.dir.file("tri.u32"));
  in.seek(first * 12);
  in.read_exact(out, count * 12);
}

}  // namespace meshsal
