// meshsal: tiled simplification's passes over a mesh on disk (simplify_file, out of core).
// The in-memory driver (tiles/simplify_tiled.cpp) keeps the mesh between passes in
// memory; here it lives in two files, and each pass reads one group at a time:
//   state      per global vertex id: x, y, z (local floats) and the carried attributes;
//   triangles  3 global ids per triangle, in the order the in-memory driver holds them.
// A pass groups its triangles by their centroid's cell (the same TileGrid), cuts each
// group with its guards from bucket files, simplifies it with the shared step
// (tiles/tile_pass.h) and appends the result; so both drivers make the same collapses
// and the same mesh, to the bit.
#pragma once
#include <cstdint>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "tiles/scratch_files.h"
#include "tiles/tile_grid.h"
#include "tiles/tile_pass.h"

namespace meshsal {

// One bit per vertex (global id): nv / 8 bytes, the only per-vertex memory of the passes.
class VertexBits {
 public:
  explicit VertexBits(uint64_t n = 0) : words_((n + 63) / 64, 0) {}
  explicit VertexBits(std::vector<uint64_t> words) : words_(std::move(words)) {}
  bool operator[](uint32_t v) const { return (words_[v >> 6] >> (v & 63)) & 1; }
  void set(uint32_t v) { words_[v >> 6] |= uint64_t(1) << (v & 63); }
  void clear(uint32_t v) { words_[v >> 6] &= ~(uint64_t(1) << (v & 63)); }
  bool any(const uint32_t* c) const { return (*this)[c[0]] || (*this)[c[1]] || (*this)[c[2]]; }
  const std::vector<uint64_t>& words() const { return words_; }

 private:
  std::vector<uint64_t> words_;
};

struct DiskMesh {
  const ScratchDir* dir = nullptr;
  uint64_t vertices = 0;                     // global ids: [0, vertices)
  std::vector<std::string> attribute_names;  // floats per vertex after x, y, z
  double origin[3] = {0, 0, 0};
  std::string state;          // file: per id, 3 + attribute_names.size() floats
  std::string triangles;      // file: 3 uint32 global ids per triangle
  uint64_t triangle_count = 0;
  std::string weights;        // file: one double per id; "" = none
  int passes = 0;             // passes run (their bucket files' names)
  size_t record_bytes() const { return 4 * (3 + attribute_names.size()); }
  uint32_t last_id() const { return uint32_t(vertices > 0 ? vertices - 1 : 0); }  // (rank_ids' bound)
};

// One pass: which triangles it simplifies and how.
struct DiskPass {
  detail::TileGrid grid;
  detail::PassBudget budget;
  // Strip passes: a triangle is selected when it touches `selected_near`, and a triangle
  // can be a guard only when it touches `guard_near` (the selected triangles' corners).
  // Null: the first pass, every triangle selected.
  const VertexBits* selected_near = nullptr;
  const VertexBits* guard_near = nullptr;
};

// Runs `pass` over `mesh` (its triangles file is replaced by the pass's result, the moved
// vertices are written into its state), clearing the vertices the pass freed in
// `pending`. `buffer_bytes`: how much the bucket buffers may hold before they go to disk.
// The groups run side by side on options.threads (group_workers.h), at most `concurrent`
// at once (each holds its piece; 0 = no cap).
// With options.exchange every process calls it alike: each buckets its share of the
// triangles and simplifies its share of the groups (pass_exchange.h) in the one folder they
// all reach (a strip pass's selected_near and guard_near on every process); rank 0 alone
// writes the result and keeps `pending`; all get the result's triangle count.
void run_disk_pass(DiskMesh& mesh, const DiskPass& pass, const SimplifyOptions& options, VertexBits& pending,
                   detail::PassTotals& totals, size_t buffer_bytes, unsigned concurrent,
                   const std::function<void(double)>& progress);

// The strips of the next pass (simplify_tiled.cpp's strip_triangles with one ring): near1
// = the pending vertices and the corners of every triangle at one, near2 = the corners of
// the triangles touching near1 (the selected ones). Returns how many are selected.
uint64_t strip_vertices(const DiskMesh& mesh, const VertexBits& pending, VertexBits& near1, VertexBits& near2);

// Rank 0's bits to every process (through a file of the folder they share; no exchange:
// nothing to do). Every process calls it alike.
void share_vertex_bits(const DiskMesh& mesh, TileExchange* exchange, VertexBits& bits, const std::string& name);

}  // namespace meshsal
