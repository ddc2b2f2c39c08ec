// The passes of tiled simplification over a mesh on disk, see disk_simplify.h.
#include "tiles/disk_simplify.h"

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <map>
#include <optional>

#include "core/cancel.h"
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

// Positions of a chunk of triangles' corners: the sorted ids and their records.
struct CornerStates {
  std::vector<uint32_t> ids;
  std::vector<uint8_t> records;
  size_t record_bytes = 0;
  void read(const DiskMesh& mesh, const uint32_t* corners, size_t n) {
    ids.assign(corners, corners + n);
    std::sort(ids.begin(), ids.end());
    ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
    record_bytes = mesh.record_bytes();
    records.resize(ids.size() * record_bytes);
    read_records(mesh.state, record_bytes, ids, records.data());
  }
  const float* position(uint32_t id) const {
    const size_t i = size_t(std::lower_bound(ids.begin(), ids.end(), id) - ids.begin());
    return reinterpret_cast<const float*>(&records[i * record_bytes]);
  }
};

class Buckets {
 public:
  // `owner`: this process writes the buckets (and removes them); the others read them.
  Buckets(const DiskMesh& mesh, int pass, size_t buffer_bytes, bool owner)
      : mesh_(mesh), pass_(pass), flush_at_(std::max<size_t>(kChunk, buffer_bytes / sizeof(BucketFace))),
        owner_(owner) {}
  ~Buckets() {
    if (owner_)
      for (const auto& [cell, own] : cells_) std::remove(path(cell).c_str());
  }
  // The owner's list of buckets to every process sharing the pass; once they have it, the
  // owner's files are complete.
  void share(TileExchange* exchange) {
    if (!exchange) return;
    TileBytes b;
    if (owner_)
      for (const auto& [cell, own] : cells_) b.put(cell), b.put(uint8_t(own));
    const auto all = tile_gather(exchange, b.data);
    if (owner_) return;
    cells_.clear();
    for (TileBytesReader in{all[0]}; !in.done();) {
      const uint64_t cell = in.get<uint64_t>();
      cells_[cell] = in.get<uint8_t>() != 0;
    }
  }
  void add(uint64_t cell, const BucketFace& face) {
    pending_[cell].push_back(face);
    cells_[cell] |= face.own != 0;
    if (++count_ >= flush_at_) flush();
  }
  void flush() {
    for (auto& [cell, faces] : pending_) {
      ScratchWriter out(path(cell), true);
      out.write_vector(faces);
      out.close();
    }
    pending_.clear();
    count_ = 0;
  }
  // The cells with a group of their own, increasing.
  std::vector<uint64_t> groups() const {
    std::vector<uint64_t> g;
    for (const auto& [cell, own] : cells_)
      if (own) g.push_back(cell);
    return g;
  }
  std::vector<BucketFace> read(uint64_t cell) const {
    if (!cells_.count(cell)) return {};
    const std::vector<uint8_t> bytes = read_scratch_file(path(cell));
    std::vector<BucketFace> faces(bytes.size() / sizeof(BucketFace));
    if (!faces.empty()) std::memcpy(faces.data(), bytes.data(), faces.size() * sizeof(BucketFace));
    return faces;
  }

 private:
  std::string path(uint64_t cell) const {
    return mesh_.dir->file("pass" + std::to_string(pass_) + "_cell" + std::to_string(cell) + ".bin");
  }
  const DiskMesh& mesh_;
  int pass_;
  size_t flush_at_, count_ = 0;
  bool owner_;
  std::map<uint64_t, std::vector<BucketFace>> pending_;
  std::map<uint64_t, bool> cells_;  // every bucket written, and whether it holds a group
};

// Every chunk of the mesh's triangles, with its index of the first.
void for_each_chunk(const DiskMesh& mesh, const std::function<void(uint64_t, const std::vector<uint32_t>&)>& body) {
  ScratchReader in(mesh.triangles);
  std::vector<uint32_t> buf(3 * kChunk);
  uint64_t first = 0;
  for (size_t got; (got = in.read(buf.data(), buf.size() * 4) / 12) > 0; first += got) {
    buf.resize(3 * got);
    body(first, buf);
    buf.resize(3 * kChunk);
  }
}

// Group `cell`'s piece: its own triangles (increasing index), then the guards (the other
// triangles at their corners, increasing index), as simplify_tiled.cpp's cut_piece makes it.
TilePiece cut_disk_piece(const DiskMesh& mesh, const Buckets& buckets, const TileGrid& grid, uint64_t cell) {
  const std::vector<BucketFace> here = buckets.read(cell);
  std::vector<BucketFace> own, guards;
  for (const BucketFace& b : here)
    if (b.own) own.push_back(b);
  auto by_index = [](const BucketFace& a, const BucketFace& b) { return a.f < b.f; };
  std::sort(own.begin(), own.end(), by_index);
  std::vector<uint32_t> own_index(own.size()), corners;
  for (size_t i = 0; i < own.size(); ++i) {
    own_index[i] = own[i].f;
    corners.insert(corners.end(), own[i].c, own[i].c + 3);
  }
  std::sort(corners.begin(), corners.end());
  corners.erase(std::unique(corners.begin(), corners.end()), corners.end());
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
      if (!contains(own_index, b.f) &&
          (contains(corners, b.c[0]) || contains(corners, b.c[1]) || contains(corners, b.c[2])))
        guards.push_back(b);
  }
  std::sort(guards.begin(), guards.end(), by_index);
  guards.erase(std::unique(guards.begin(), guards.end(), [](const BucketFace& a, const BucketFace& b) { return a.f == b.f; }),
               guards.end());

  TilePiece p;
  std::vector<uint32_t>& ids = p.ids;
  for (const auto* list : {&own, &guards})
    for (const BucketFace& b : *list) ids.insert(ids.end(), b.c, b.c + 3);
  std::sort(ids.begin(), ids.end());
  ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
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
  auto local = [&](uint32_t id) { return uint32_t(std::lower_bound(ids.begin(), ids.end(), id) - ids.begin()); };
  for (const BucketFace& b : own)
    for (int k = 0; k < 3; ++k) p.mesh.triangles.push_back(local(b.c[k]));
  for (const BucketFace& b : guards)
    for (int k = 0; k < 3; ++k) {
      p.mesh.triangles.push_back(local(b.c[k]));
      p.pinned[local(b.c[k])] = 1;
    }
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

namespace {

// Whether the pass selects triangle c (every triangle in a first pass).
bool selected(const DiskPass& pass, const uint32_t* c) { return !pass.selected_near || pass.selected_near->any(c); }

// Each selected triangle to its group's bucket; each triangle that may be a guard to the
// bucket of every cell its corners lie in.
void fill_buckets(const DiskMesh& mesh, const DiskPass& pass, Buckets& buckets) {
  CornerStates states;
  for_each_chunk(mesh, [&](uint64_t first, const std::vector<uint32_t>& t) {
    throw_if_cancelled();
    states.read(mesh, t.data(), t.size());
    for (size_t i = 0; i < t.size(); i += 3) {
      const uint32_t* c = &t[i];
      const bool mine = selected(pass, c);
      if (!mine && pass.guard_near && !pass.guard_near->any(c)) continue;
      const BucketFace face{uint32_t(first + i / 3), {c[0], c[1], c[2]}, 0};
      const float* p[3] = {states.position(c[0]), states.position(c[1]), states.position(c[2])};
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
  });
  buckets.flush();
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

// Each group's goal from the common error level (tile_pass.h), in every pass; the levels
// of each group kept on disk meanwhile.
std::vector<size_t> group_goals(const DiskMesh& mesh, const DiskPass& pass, const Buckets& buckets,
                                const std::vector<uint64_t>& groups, const SimplifyOptions& options,
                                const std::function<void(double)>& progress) {
  auto levels_file = [&](size_t g) { return mesh.dir->file("levels_" + std::to_string(g) + ".f64"); };
  // This process's groups (pass_exchange.h): their levels to files, their counts shared.
  std::vector<uint64_t> faces(groups.size(), 0), first_goals(groups.size(), 0), counts(groups.size(), 0);
  for (size_t g = 0; g < groups.size(); ++g) {
    if (!runs_group(options.exchange, g)) continue;
    throw_if_cancelled();
    if (progress) progress(0.5 * double(g) / double(groups.size()));
    const TilePiece tile = cut_disk_piece(mesh, buckets, pass.grid, groups[g]);
    const std::vector<double> w = piece_weights(mesh, tile);
    const std::vector<double> levels = collapse_levels(tile, mesh.weights.empty() ? nullptr : &w, options);
    ScratchWriter lf(levels_file(g));
    lf.write_vector(levels);
    lf.close();
    faces[g] = tile.mesh.triangle_count() - tile.guards;
    if (pass.budget.rule == Targets::FirstPass) first_goals[g] = first_pass_goal(tile, pass.budget.ratio);
    counts[g] = levels.size();
  }
  for (auto* v : {&faces, &first_goals, &counts}) share_group_values(options.exchange, *v);
  uint64_t goal_sum = 0, count = 0;
  std::vector<size_t> sizes;
  for (size_t g = 0; g < groups.size(); ++g) {
    sizes.push_back(size_t(faces[g]));
    goal_sum += first_goals[g];
    count += counts[g];
  }
  // Rank 0 reads every group's levels (the others need only the goals) and removes them.
  std::vector<uint64_t> goals(groups.size(), 0);
  lead_step(options.exchange, [&] {
    const std::vector<size_t> found = pass_goals(pass.budget, sizes, goal_sum, count, [&](size_t g) {
      const std::vector<uint8_t> bytes = read_scratch_file(levels_file(g));
      std::vector<double> levels(bytes.size() / 8);
      // (A group with no collapse has an empty file: memcpy's pointers would be null.)
      if (!levels.empty()) std::memcpy(levels.data(), bytes.data(), bytes.size());
      return levels;
    });
    goals.assign(found.begin(), found.end());
    for (size_t g = 0; g < groups.size(); ++g) std::remove(levels_file(g).c_str());
  });
  share_rank0_values(options.exchange, goals);
  return std::vector<size_t>(goals.begin(), goals.end());
}

// Writes the moved vertices' records (id, then the state record) into the state file, a
// block at a time: only once every group has read the pass's input.
void apply_moves(DiskMesh& mesh, const std::string& moves) {
  const size_t rec = mesh.record_bytes();
  ScratchReader in(moves);
  std::vector<uint8_t> buf((4 + rec) * kChunk), data;
  std::vector<uint32_t> ids;
  for (size_t got; (got = in.read(buf.data(), buf.size()) / (4 + rec)) > 0;) {
    ids.resize(got);
    data.resize(got * rec);
    for (size_t i = 0; i < got; ++i) {
      std::memcpy(&ids[i], &buf[i * (4 + rec)], 4);
      std::memcpy(&data[i * rec], &buf[i * (4 + rec) + 4], rec);
    }
    write_records(mesh.state, rec, ids, data.data());
  }
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
                   PassTotals& totals, size_t buffer_bytes, const std::function<void(double)>& progress) {
  // With an exchange (pass_exchange.h) rank 0, the lead, fills the buckets and writes the
  // pass's result; every process simplifies its share of the groups.
  TileExchange* exchange = options.exchange;
  const bool lead = !exchange || exchange->rank() == 0;
  Buckets buckets(mesh, ++mesh.passes, buffer_bytes, lead);
  lead_step(exchange, [&] { fill_buckets(mesh, pass, buckets); });
  buckets.share(exchange);
  const std::vector<uint64_t> groups = buckets.groups();
  const std::vector<size_t> goals = group_goals(mesh, pass, buckets, groups, options, progress);

  // Each group in cell order (the in-memory driver's order), then the rest as it was. Shared,
  // each process leaves its groups' outcomes in a file each, appended by the lead in order.
  const std::string next = mesh.triangles + "+";
  const std::string moves = mesh.dir->file("moves.bin");
  auto group_file = [&](size_t g) { return mesh.dir->file("group_" + std::to_string(g) + ".bin"); };
  std::optional<ScratchWriter> out, moved;
  if (lead) out.emplace(next), moved.emplace(moves);
  uint64_t out_count = 0;
  auto append = [&](const std::vector<uint32_t>& triangles, const std::vector<uint8_t>& records,
                    const std::vector<uint32_t>& freed) {
    out->write_vector(triangles);
    out_count += triangles.size() / 3;
    moved->write_vector(records);
    for (uint32_t id : freed) pending.clear(id);
  };
  PassTotals mine;
  for (size_t g = 0; g < groups.size(); ++g) {
    if (!runs_group(exchange, g)) continue;
    throw_if_cancelled();
    if (progress) progress(0.5 + 0.5 * double(g) / double(groups.size()));
    const TilePiece tile = cut_disk_piece(mesh, buckets, pass.grid, groups[g]);
    const std::vector<double> w = piece_weights(mesh, tile);
    const TilePiece piece = simplify_group(tile, mesh.weights.empty() ? nullptr : &w, options, goals[g], mine);
    std::vector<uint32_t> triangles;
    std::vector<uint8_t> records;
    piece_records(mesh, piece, triangles, records);
    if (!exchange) {
      append(triangles, records, freed_ids(tile));
      continue;
    }
    TileBytes b;
    b.put(triangles);
    b.put(records);
    b.put(freed_ids(tile));
    ScratchWriter f(group_file(g));
    f.write_vector(b.data);
    f.close();
  }
  add_totals(totals, share_totals(exchange, mine));  // (shared: every group's file is complete)
  lead_step(exchange, [&] {
    if (exchange)
      for (size_t g = 0; g < groups.size(); ++g) {
        const std::vector<uint8_t> bytes = read_scratch_file(group_file(g));
        TileBytesReader in{bytes};
        const std::vector<uint32_t> triangles = in.get_vector<uint32_t>();
        const std::vector<uint8_t> records = in.get_vector<uint8_t>();
        append(triangles, records, in.get_vector<uint32_t>());
        std::remove(group_file(g).c_str());
      }
    if (pass.selected_near)
      for_each_chunk(mesh, [&](uint64_t, const std::vector<uint32_t>& t) {
        for (size_t i = 0; i < t.size(); i += 3)
          if (!selected(pass, &t[i])) {
            out->write(&t[i], 12);
            ++out_count;
          }
      });
    out->close();
    moved->close();
    apply_moves(mesh, moves);
    std::remove(moves.c_str());
    if (std::rename(next.c_str(), mesh.triangles.c_str()) != 0)
      throw Error(mesh.triangles + ": cannot replace a temporary file");
  });
  // The lead's count; once the others have it, its files are the next pass's input.
  mesh.triangle_count = share_rank0_value(exchange, out_count);
  if (progress) progress(1.0);
}

}  // namespace meshsal
