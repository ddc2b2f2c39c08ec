// The passes of tiled simplification over a mesh on disk, see disk_simplify.h.
#include "tiles/disk_simplify.h"

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <map>
#include <atomic>
#include <thread>
#include <optional>

#include "core/cancel.h"
#include "core/id_ranks.h"
#include "tiles/group_workers.h"
#include "tiles/pass_exchange.h"
#include "tiles/tile_bytes.h"
#include "tiles/tile_reduce.h"

namespace meshsal {

using namespace detail;

namespace {

constexpr size_t kChunk = 1 << 16;  // triangles per read

// A triangle in a bucket file: its index in the pass's triangles, its corners, and whether
// the bucket is its group's (own) or that of a tile one of its corners lies in.
struct BucketFace {
  uint32_t f, c[3], own;
};

bool contains(const std::vector<uint32_t>& sorted, uint32_t x) {
  return std::binary_search(sorted.begin(), sorted.end(), x);
}

// Positions of a chunk of triangles' corners: the distinct ids, their records, and each
// corner's place among them.
struct CornerStates {
  std::vector<uint32_t> ids, rank;
  std::vector<uint8_t> records;
  size_t record_bytes = 0;
  void read(const DiskMesh& mesh, const uint32_t* corners, size_t n) {
    rank_ids(corners, n, mesh.last_id(), ids, rank, 0);
    record_bytes = mesh.record_bytes();
    records.resize(ids.size() * record_bytes);
    read_records(mesh.state, record_bytes, ids, records.data());
  }
  // Corner i of the chunk read.
  const float* position(size_t i) const { return reinterpret_cast<const float*>(&records[rank[i] * record_bytes]); }
};

// A pass's buckets: per cell, the triangles of its group (own) and those at its vertices.
// Each process fills its share of the triangles into files of its own (a cell's bucket is
// every process's file in rank order: each in triangle order, the ranks' shares in order).
class Buckets {
 public:
  Buckets(const DiskMesh& mesh, int pass, size_t buffer_bytes, int rank)
      : mesh_(mesh), pass_(pass), flush_at_(std::max<size_t>(kChunk, buffer_bytes / sizeof(BucketFace))),
        rank_(rank) {}
  ~Buckets() {  // this process's files (every process is past reading them: share_totals)
    for (const auto& cell : mine_) std::remove(path(cell.first, rank_).c_str());  // (a cell not yet flushed: no file)
  }
  // Every process's cells to every process, once each has filled its share.
  void share(TileExchange* exchange) {
    TileBytes b;
    for (const auto& [cell, own] : mine_) b.put(cell), b.put(own);
    const auto all = tile_gather(exchange, b.data);
    cells_.clear();
    for (size_t r = 0; r < all.size(); ++r)
      for (TileBytesReader in{all[r]}; !in.done();) {
        const uint64_t cell = in.get<uint64_t>();
        Cell& c = cells_[cell];
        c.own += in.get<uint64_t>();
        c.writers.push_back(int(r));
      }
  }
  void add(uint64_t cell, const BucketFace& face) {
    pending_[cell].push_back(face);
    mine_[cell] += face.own;
    if (++count_ >= flush_at_) flush();
  }
  void flush() {
    for (auto& [cell, faces] : pending_) {
      ScratchWriter out(path(cell, rank_), true);
      out.write_vector(faces);
      out.close();
    }
    pending_.clear();
    count_ = 0;
  }
  // The cells with a group of their own, increasing, and each one's own triangles.
  std::vector<uint64_t> groups(std::vector<size_t>& sizes) const {
    std::vector<uint64_t> g;
    sizes.clear();
    for (const auto& [cell, c] : cells_)
      if (c.own) g.push_back(cell), sizes.push_back(size_t(c.own));
    return g;
  }
  std::vector<BucketFace> read(uint64_t cell) const {
    const auto it = cells_.find(cell);
    if (it == cells_.end()) return {};
    std::vector<BucketFace> faces;
    for (const int r : it->second.writers) append_scratch_records(path(cell, r), faces);
    return faces;
  }

 private:
  struct Cell {
    uint64_t own = 0;          // its group's triangles, over every process
    std::vector<int> writers;  // the processes with a file of it, in rank order
  };
  std::string path(uint64_t cell, int rank) const {
    return mesh_.dir->file("pass" + std::to_string(pass_) + "_cell" + std::to_string(cell) + "_r" +
                           std::to_string(rank) + ".bin");
  }
  const DiskMesh& mesh_;
  int pass_;
  size_t flush_at_, count_ = 0;
  int rank_;
  std::map<uint64_t, std::vector<BucketFace>> pending_;
  std::map<uint64_t, uint64_t> mine_;  // this process's cells and their own triangles
  std::map<uint64_t, Cell> cells_;     // every process's, once shared
};

// Every chunk of the mesh's triangles [begin, end) (all of them by default), with its index
// of the first.
void for_each_chunk(const DiskMesh& mesh, const std::function<void(uint64_t, const std::vector<uint32_t>&)>& body,
                    uint64_t begin = 0, uint64_t end = UINT64_MAX) {
  end = std::min(end, mesh.triangle_count);
  ScratchReader in(mesh.triangles);
  in.seek(begin * 12);
  std::vector<uint32_t> buf(3 * kChunk);
  for (uint64_t first = begin; first < end;) {
    const size_t want = size_t(std::min<uint64_t>(kChunk, end - first));
    buf.resize(3 * want);
    in.read_exact(buf.data(), 12 * want);
    body(first, buf);
    first += want;
  }
}

// Group `cell`'s piece: its own triangles (increasing index), then the guards (the other
// triangles at their corners, increasing index), as simplify_tiled.cpp's cut_piece makes it.
// `mark`: one bit per vertex, all clear (left clear): the piece's corners while it is cut.
TilePiece cut_disk_piece(const DiskMesh& mesh, const Buckets& buckets, const TileGrid& grid, uint64_t cell,
                         VertexBits& mark) {
  const std::vector<BucketFace> here = buckets.read(cell);
  std::vector<BucketFace> own, guards;
  for (const BucketFace& b : here)
    if (b.own) own.push_back(b);
  // (A bucket is written in triangle order: this sort finds it sorted.)
  auto by_index = [](const BucketFace& a, const BucketFace& b) { return a.f < b.f; };
  if (!std::is_sorted(own.begin(), own.end(), by_index)) std::sort(own.begin(), own.end(), by_index);
  const uint32_t max_id = mesh.last_id();
  std::vector<uint32_t> own_index(own.size()), corners, local;
  {
    std::vector<uint32_t> all(3 * own.size());
    for (size_t i = 0; i < own.size(); ++i) {
      own_index[i] = own[i].f;
      for (int k = 0; k < 3; ++k) all[3 * i + k] = own[i].c[k];
    }
    rank_ids(all.data(), all.size(), max_id, corners, local);
  }
  for (uint32_t v : corners) mark.set(v);
  // Every triangle at a corner v is in the bucket of v's cell: read those.
  std::vector<uint64_t> near{cell};
  {
    std::vector<uint8_t> rec(corners.size() * mesh.record_bytes());
    read_records(mesh.state, mesh.record_bytes(), corners, rec.data());
    for (size_t i = 0; i < corners.size(); ++i) {
      const float* p = reinterpret_cast<const float*>(&rec[i * mesh.record_bytes()]);
      const double q[3] = {p[0], p[1], p[2]};
      near.push_back(grid.cell_of(q));
    }
  }
  std::sort(near.begin(), near.end());
  near.erase(std::unique(near.begin(), near.end()), near.end());
  for (uint64_t u : near) {
    const std::vector<BucketFace> faces = u == cell ? here : buckets.read(u);
    for (const BucketFace& b : faces)
      if (mark.any(b.c) && !(u == cell ? b.own : contains(own_index, b.f))) guards.push_back(b);
  }
  for (uint32_t v : corners) mark.clear(v);
  std::sort(guards.begin(), guards.end(), by_index);
  guards.erase(std::unique(guards.begin(), guards.end(), [](const BucketFace& a, const BucketFace& b) { return a.f == b.f; }),
               guards.end());

  TilePiece p;
  std::vector<uint32_t>& ids = p.ids;
  {
    std::vector<uint32_t> all;
    all.reserve(3 * (own.size() + guards.size()));
    for (const auto* list : {&own, &guards})
      for (const BucketFace& b : *list) all.insert(all.end(), b.c, b.c + 3);
    rank_ids(all.data(), all.size(), max_id, ids, local);
  }
  const size_t nv = ids.size(), nattr = mesh.attribute_names.size();
  std::vector<float> rec(nv * (3 + nattr));
  read_records(mesh.state, mesh.record_bytes(), ids, rec.data());
  p.mesh.positions.resize(3 * nv);
  for (const std::string& name : mesh.attribute_names) p.mesh.attributes.push_back({name, std::vector<float>(nv)});
  for (size_t v = 0; v < nv; ++v) {
    for (int k = 0; k < 3; ++k) p.mesh.positions[3 * v + k] = rec[v * (3 + nattr) + k];
    for (size_t a = 0; a < nattr; ++a) p.mesh.attributes[a].values[v] = rec[v * (3 + nattr) + 3 + a];
  }
  for (int k = 0; k < 3; ++k) p.mesh.origin[k] = mesh.origin[k];
  p.pinned.assign(nv, 0);
  p.mesh.triangles = std::move(local);
  for (size_t i = 3 * own.size(); i < p.mesh.triangles.size(); ++i) p.pinned[p.mesh.triangles[i]] = 1;
  p.guards = guards.size();
  return p;
}

}  // namespace

uint64_t strip_vertices(const DiskMesh& mesh, const VertexBits& pending, VertexBits& near1, VertexBits& near2) {
  near1 = pending;
  for_each_chunk(mesh, [&](uint64_t, const std::vector<uint32_t>& t) {
    for (size_t i = 0; i < t.size(); i += 3)
      if (pending.any(&t[i]))
        for (int k = 0; k < 3; ++k) near1.set(t[i + k]);
  });
  near2 = VertexBits(mesh.vertices);
  uint64_t selected = 0;
  for_each_chunk(mesh, [&](uint64_t, const std::vector<uint32_t>& t) {
    for (size_t i = 0; i < t.size(); i += 3)
      if (near1.any(&t[i])) {
        ++selected;
        for (int k = 0; k < 3; ++k) near2.set(t[i + k]);
      }
  });
  return selected;
}

void share_vertex_bits(const DiskMesh& mesh, TileExchange* exchange, VertexBits& bits, const std::string& name) {
  if (!exchange) return;
  const std::string path = mesh.dir->file(name);
  lead_step(exchange, [&] {
    ScratchWriter out(path);
    out.write_vector(bits.words());
    out.close();
  });
  all_step(exchange, [&] {
    if (exchange->rank() == 0) return;
    std::vector<uint64_t> words((mesh.vertices + 63) / 64);
    ScratchReader in(path);
    in.read_exact(words.data(), words.size() * 8);
    bits = VertexBits(std::move(words));
  });
  lead_step(exchange, [&] { std::remove(path.c_str()); });
}

namespace {

// Whether the pass selects triangle c (every triangle in a first pass).
bool selected(const DiskPass& pass, const uint32_t* c) { return !pass.selected_near || pass.selected_near->any(c); }

// Each selected triangle of [begin, end) to its group's bucket; each that may be a guard to
// the bucket of every cell its corners lie in. Returns how many the pass did not select.
uint64_t fill_buckets(const DiskMesh& mesh, const DiskPass& pass, Buckets& buckets, uint64_t begin, uint64_t end) {
  CornerStates states;
  uint64_t rest = 0;
  for_each_chunk(mesh, [&](uint64_t first, const std::vector<uint32_t>& t) {
    throw_if_cancelled();
    states.read(mesh, t.data(), t.size());
    for (size_t i = 0; i < t.size(); i += 3) {
      const uint32_t* c = &t[i];
      const bool mine = selected(pass, c);
      rest += mine ? 0 : 1;
      if (!mine && pass.guard_near && !pass.guard_near->any(c)) continue;
      const BucketFace face{uint32_t(first + i / 3), {c[0], c[1], c[2]}, 0};
      const float* p[3] = {states.position(i), states.position(i + 1), states.position(i + 2)};
      const uint64_t group = mine ? pass.grid.centroid_cell(p[0], p[1], p[2]) : UINT64_MAX;
      if (mine) buckets.add(group, BucketFace{face.f, {c[0], c[1], c[2]}, 1});
      uint64_t seen[3];
      int nseen = 0;
      for (int k = 0; k < 3; ++k) {
        const double q[3] = {p[k][0], p[k][1], p[k][2]};
        const uint64_t u = pass.grid.cell_of(q);
        if (u == group || std::find(seen, seen + nseen, u) != seen + nseen) continue;
        seen[nseen++] = u;
        buckets.add(u, face);
      }
    }
  }, begin, end);
  buckets.flush();
  return rest;
}

// The weights of a piece's vertices (empty without weights).
std::vector<double> piece_weights(const DiskMesh& mesh, const TilePiece& tile) {
  std::vector<double> w;
  if (!mesh.weights.empty()) {
    w.resize(tile.ids.size());
    read_records(mesh.weights, 8, tile.ids, w.data());
  }
  return w;
}

// Reports a pass's progress as its groups finish: this process's `count` groups, told from
// the calling thread only (the progress callback's promise), whichever worker finished.
class GroupProgress {
 public:
  GroupProgress(const std::function<void(double)>& progress, double from, double to, size_t count)
      : progress_(progress), from_(from), to_(to), count_(std::max<size_t>(1, count)),
        caller_(std::this_thread::get_id()) {}
  void one_done() {
    const size_t done = ++done_;
    if (progress_ && std::this_thread::get_id() == caller_) progress_(from_ + (to_ - from_) * double(done) / double(count_));
  }

 private:
  const std::function<void(double)>& progress_;
  double from_, to_;
  size_t count_;
  std::atomic<size_t> done_{0};
  std::thread::id caller_;
};

// How many of the pass's groups this process runs (pass_exchange.h).
size_t own_groups(const TileExchange* exchange, size_t groups) {
  size_t n = 0;
  for (size_t g = 0; g < groups; ++g) n += runs_group(exchange, g) ? 1 : 0;
  return n;
}

// What the groups of a pass run on: the workers (group_workers.h) and a mark (cut_disk_piece)
// for each.
struct PassWorkers {
  GroupWorkers split;
  SimplifyOptions inner;  // options with the threads a group may use
  std::vector<VertexBits> marks;
};

// Each group's goal from the common error level (tile_pass.h), in every pass; the levels
// of each group kept on disk meanwhile.
std::vector<size_t> group_goals(const DiskMesh& mesh, const DiskPass& pass, const Buckets& buckets,
                                const std::vector<uint64_t>& groups, const std::vector<size_t>& sizes,
                                const SimplifyOptions& options, PassWorkers& workers,
                                const std::function<void(double)>& progress) {
  auto levels_file = [&](size_t g) { return mesh.dir->file("levels_" + std::to_string(g) + ".f64"); };
  // This process's groups (pass_exchange.h): their levels to files, their counts shared.
  std::vector<uint64_t> faces(groups.size(), 0), first_goals(groups.size(), 0), counts(groups.size(), 0);
  GroupProgress done(progress, 0, 0.5, own_groups(options.exchange, groups.size()));
  for_each_group(options.exchange, sizes, workers.split.workers, [&](size_t g, unsigned worker) {
    throw_if_cancelled();
    const TilePiece tile = cut_disk_piece(mesh, buckets, pass.grid, groups[g], workers.marks[worker]);
    const std::vector<double> w = piece_weights(mesh, tile);
    const std::vector<double> levels = collapse_levels(tile, mesh.weights.empty() ? nullptr : &w, workers.inner);
    ScratchWriter lf(levels_file(g));
    lf.write_vector(levels);
    lf.close();
    faces[g] = tile.mesh.triangle_count() - tile.guards;
    if (pass.budget.rule == Targets::FirstPass) first_goals[g] = first_pass_goal(tile, pass.budget.ratio);
    counts[g] = levels.size();
    done.one_done();
  });
  for (auto* v : {&faces, &first_goals, &counts}) share_group_values(options.exchange, *v);
  uint64_t goal_sum = 0, count = 0;
  std::vector<size_t> own_faces;
  for (size_t g = 0; g < groups.size(); ++g) {
    own_faces.push_back(size_t(faces[g]));
    goal_sum += first_goals[g];
    count += counts[g];
  }
  // Rank 0 reads every group's levels (the others need only the goals) and removes them.
  std::vector<uint64_t> goals(groups.size(), 0);
  lead_step(options.exchange, [&] {
    const std::vector<size_t> found = pass_goals(pass.budget, own_faces, goal_sum, count, [&](size_t g) {
      std::vector<double> levels;  // (a group with no collapse: an empty file)
      append_scratch_records(levels_file(g), levels);
      return levels;
    });
    goals.assign(found.begin(), found.end());
    for (size_t g = 0; g < groups.size(); ++g) std::remove(levels_file(g).c_str());
  });
  share_rank0_values(options.exchange, goals);
  return std::vector<size_t>(goals.begin(), goals.end());
}

// Writes a group's moved vertices' records (id, then the state record) into the state
// file: only once every group has read the pass's input. (A vertex moves in one group
// alone: the one that freed it.)
void apply_moves(const DiskMesh& mesh, const std::vector<uint8_t>& moves) {
  const size_t rec = mesh.record_bytes(), n = moves.size() / (4 + rec);
  std::vector<uint32_t> ids(n);
  std::vector<uint8_t> data(n * rec);
  for (size_t i = 0; i < n; ++i) {
    std::memcpy(&ids[i], &moves[i * (4 + rec)], 4);
    std::memcpy(&data[i * rec], &moves[i * (4 + rec) + 4], rec);
  }
  write_records(mesh.state, rec, ids, data.data());
}

}  // namespace

namespace {

// A group's piece as the pass's files take it: its triangles (global ids) to `triangles`,
// its moved vertices (id, then the state record) to `moves`. Pinned vertices are as they
// were (simplify_tile restores them); the rest may have moved.
void piece_records(const DiskMesh& mesh, const TilePiece& piece, std::vector<uint32_t>& triangles,
                   std::vector<uint8_t>& moves) {
  for (uint32_t v : piece.mesh.triangles) triangles.push_back(piece.ids[v]);
  const size_t rec = mesh.record_bytes(), nattr = mesh.attribute_names.size();
  std::vector<uint8_t> record(4 + rec);
  for (size_t v = 0; v < piece.ids.size(); ++v) {
    if (piece.pinned[v]) continue;
    std::memcpy(&record[0], &piece.ids[v], 4);
    std::memcpy(&record[4], &piece.mesh.positions[3 * v], 12);
    for (size_t a = 0; a < nattr; ++a) std::memcpy(&record[16 + 4 * a], &piece.mesh.attributes[a].values[v], 4);
    moves.insert(moves.end(), record.begin(), record.end());
  }
}

}  // namespace

void run_disk_pass(DiskMesh& mesh, const DiskPass& pass, const SimplifyOptions& options, VertexBits& pending,
                   PassTotals& totals, size_t buffer_bytes, unsigned concurrent,
                   const std::function<void(double)>& progress) {
  // With an exchange (pass_exchange.h) every process buckets its share of the triangles and
  // simplifies its share of the groups; rank 0, the lead, writes the pass's result.
  TileExchange* exchange = options.exchange;
  const int rank = exchange ? exchange->rank() : 0, ranks = exchange ? exchange->ranks() : 1;
  Buckets buckets(mesh, ++mesh.passes, buffer_bytes, rank);
  const uint64_t n = mesh.triangle_count;
  const uint64_t n0 = n * uint64_t(rank) / uint64_t(ranks), n1 = n * uint64_t(rank + 1) / uint64_t(ranks);
  uint64_t my_rest = 0;  // this process's share of the triangles the pass did not select
  all_step(exchange, [&] { my_rest = fill_buckets(mesh, pass, buckets, n0, n1); });
  buckets.share(exchange);
  std::vector<size_t> sizes;
  const std::vector<uint64_t> groups = buckets.groups(sizes);
  PassWorkers workers;
  workers.split = group_workers(options.threads, concurrent, groups.size());
  workers.inner = options;
  workers.inner.threads = workers.split.inner;
  workers.marks.assign(workers.split.workers, VertexBits(mesh.vertices));
  const std::vector<size_t> goals = group_goals(mesh, pass, buckets, groups, sizes, options, workers, progress);

  // Each group's outcome to files of its own (the groups run side by side, and shared, on
  // other processes too): its triangles and moved vertices, and the ids it freed.
  const std::string next = mesh.triangles + "+";
  auto group_file = [&](size_t g) { return mesh.dir->file("group_" + std::to_string(g) + ".bin"); };
  auto freed_file = [&](size_t g) { return mesh.dir->file("freed_" + std::to_string(g) + ".u32"); };
  std::vector<PassTotals> group_totals(groups.size());
  std::vector<uint64_t> out_faces(groups.size(), 0);
  GroupProgress done(progress, 0.5, 1.0, own_groups(exchange, groups.size()));
  for_each_group(exchange, sizes, workers.split.workers, [&](size_t g, unsigned worker) {
    throw_if_cancelled();
    const TilePiece tile = cut_disk_piece(mesh, buckets, pass.grid, groups[g], workers.marks[worker]);
    const std::vector<double> w = piece_weights(mesh, tile);
    const TilePiece piece =
        simplify_group(tile, mesh.weights.empty() ? nullptr : &w, workers.inner, goals[g], group_totals[g]);
    std::vector<uint32_t> triangles;
    std::vector<uint8_t> records;
    piece_records(mesh, piece, triangles, records);
    out_faces[g] = triangles.size() / 3;
    TileBytes b;
    b.put(triangles);
    b.put(records);
    ScratchWriter f(group_file(g));
    f.write_vector(b.data);
    f.close();
    ScratchWriter freed(freed_file(g));
    freed.write_vector(freed_ids(tile));
    freed.close();
    done.one_done();
  });
  PassTotals mine;
  for (const PassTotals& t : group_totals) add_totals(mine, t);
  add_totals(totals, share_totals(exchange, mine));  // (shared: every group's files are complete)

  // The pass's triangles: each group's in group order (the in-memory driver's), then the
  // rest as they were (a strip pass); each process writes its groups' and its share of the
  // rest where they go, and moves its groups' vertices (every group has read the input).
  share_group_values(exchange, out_faces);
  std::vector<uint64_t> at(groups.size() + 1, 0);
  for (size_t g = 0; g < groups.size(); ++g) at[g + 1] = at[g] + out_faces[g];
  std::vector<uint64_t> rest;  // every process's, in rank order
  {
    TileBytes b;
    b.put(my_rest);
    for (const auto& bytes : tile_gather(exchange, b.data)) rest.push_back(TileBytesReader{bytes}.get<uint64_t>());
  }
  lead_step(exchange, [&] { ScratchWriter(next).close(); });
  all_step(exchange, [&] {
    for (size_t g = 0; g < groups.size(); ++g) {
      if (!runs_group(exchange, g)) continue;
      const std::vector<uint8_t> bytes = read_scratch_file(group_file(g));
      TileBytesReader in{bytes};
      const std::vector<uint32_t> triangles = in.get_vector<uint32_t>();
      ScratchWriter out(next, at[g] * 12);
      out.write_vector(triangles);
      out.close();
      apply_moves(mesh, in.get_vector<uint8_t>());
      std::remove(group_file(g).c_str());
    }
    if (!pass.selected_near) return;
    uint64_t first = at.back();
    for (int r = 0; r < rank; ++r) first += rest[size_t(r)];
    ScratchWriter out(next, first * 12);
    for_each_chunk(mesh, [&](uint64_t, const std::vector<uint32_t>& t) {
      for (size_t i = 0; i < t.size(); i += 3)
        if (!selected(pass, &t[i])) out.write(&t[i], 12);
    }, n0, n1);
    out.close();
  });
  uint64_t out_count = at.back();
  for (const uint64_t r : rest) out_count += r;
  // Rank 0 keeps the pending vertices (the strips are its to select) and puts the pass's
  // triangles in place.
  lead_step(exchange, [&] {
    for (size_t g = 0; g < groups.size(); ++g) {
      std::vector<uint32_t> ids;
      append_scratch_records(freed_file(g), ids);
      for (uint32_t id : ids) pending.clear(id);
      std::remove(freed_file(g).c_str());
    }
    if (std::rename(next.c_str(), mesh.triangles.c_str()) != 0)
      throw Error(mesh.triangles + ": cannot replace a temporary file");
  });
  // The lead's count; once the others have it, its files are the next pass's input.
  mesh.triangle_count = share_rank0_value(exchange, out_count);
  if (progress) progress(1.0);
}

}  // namespace meshsal
