// meshsal: tiled simplification (meshsal.h, simplify_mesh_tiled). Pass 1 simplifies each
// tile alone with the vertices it shares with other tiles pinned; each strip pass then
// simplifies the triangles around the vertices still pinned, grouped by a grid shifted by
// half a tile (so a cut of the last pass lies inside a strip), toward what is left of the
// target. A shared vertex is pinned in every piece that has it, so the pieces join on it:
// no crack, and no border edge that the input did not have.
#include "tiles/simplify_tiled.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

#include "core/mesh_context.h"
#include "core/cancel.h"
#include "core/mesh_points.h"
#include "core/model_frame.h"
#include "core/timer.h"
#include "simplify/simplify.h"
#include "tiles/group_workers.h"
#include "tiles/pass_exchange.h"
#include "tiles/tile_grid.h"
#include "tiles/tile_pass.h"
#include "tiles/tile_pieces.h"
#include "tiles/tile_rounds.h"

namespace meshsal {

using namespace detail;

namespace {

// The mesh being simplified between passes: its vertices carry global (input) ids.
struct Work {
  Mesh mesh;
  std::vector<uint32_t> ids;  // increasing
};

// One pass: the triangles `selected` of work, grouped by `grid`, each group simplified as a
// tile; the rest pass through. `pending` (per global id): vertices not yet free in any
// pass; on return only those that this pass had to pin.
Work run_pass(const Work& work, const std::vector<uint32_t>& selected, const TileGrid& grid, const PassBudget& budget,
              const std::vector<double>* weights, const SimplifyOptions& options, std::vector<uint8_t>& pending,
              PassTotals& totals) {
  const std::vector<std::pair<uint64_t, uint32_t>> cells = triangles_by_cell(work.mesh, selected, grid);
  const size_t nt = work.mesh.triangle_count();
  std::vector<uint32_t> group(nt, UINT32_MAX);  // UINT32_MAX: not selected
  std::vector<std::vector<uint32_t>> groups;
  for (size_t i = 0; i < cells.size(); ++i) {
    if (i == 0 || cells[i].first != cells[i - 1].first) groups.emplace_back();
    groups.back().push_back(cells[i].second);
    group[cells[i].second] = uint32_t(groups.size() - 1);
  }
  const VertexTriangles around = vertex_triangles(work.mesh);
  auto weights_of = [&](const TilePiece& tile) {
    std::vector<double> w;
    if (weights) {
      w.resize(tile.ids.size());
      for (size_t i = 0; i < w.size(); ++i) w[i] = (*weights)[tile.ids[i]];
    }
    return w;
  };
  // Each group's goal from the common error level (tile_pass.h), in every pass. With an
  // exchange this process runs its share of the groups (pass_exchange.h) and gets the rest.
  // The groups run side by side (group_workers.h), each outcome in its own slot.
  TileExchange* exchange = options.exchange;
  std::vector<size_t> sizes;
  for (const std::vector<uint32_t>& g : groups) sizes.push_back(g.size());
  const GroupWorkers workers = group_workers(options.threads, 0, groups.size());
  SimplifyOptions inner = options;
  inner.threads = workers.inner;
  std::vector<std::vector<double>> levels(groups.size());
  std::vector<uint64_t> first_goals(groups.size(), 0);
  for_each_group(exchange, sizes, workers.workers, [&](size_t g, unsigned) {
    throw_if_cancelled();
    const TilePiece tile = cut_piece(work.mesh, work.ids, &around, group, uint32_t(g), groups[g]);
    const std::vector<double> w = weights_of(tile);
    levels[g] = collapse_levels(tile, weights ? &w : nullptr, inner);
    if (budget.rule == Targets::FirstPass) first_goals[g] = first_pass_goal(tile, budget.ratio);
  });
  share_group_levels(exchange, levels);
  share_group_values(exchange, first_goals);
  uint64_t goal_sum = 0, count = 0;
  for (size_t g = 0; g < groups.size(); ++g) goal_sum += first_goals[g], count += levels[g].size();
  const std::vector<size_t> goals =
      pass_goals(budget, sizes, goal_sum, count, [&](size_t g) { return levels[g]; });
  std::vector<std::vector<double>>().swap(levels);
  std::vector<GroupOutcome> outcomes(groups.size());
  std::vector<PassTotals> group_totals(groups.size());
  for_each_group(exchange, sizes, workers.workers, [&](size_t g, unsigned) {
    throw_if_cancelled();
    const TilePiece tile = cut_piece(work.mesh, work.ids, &around, group, uint32_t(g), groups[g]);
    const std::vector<double> w = weights_of(tile);
    outcomes[g].piece = simplify_group(tile, weights ? &w : nullptr, inner, goals[g], group_totals[g]);
    outcomes[g].freed = freed_ids(tile);
  });
  PassTotals pass;
  for (const PassTotals& t : group_totals) add_totals(pass, t);
  share_group_outcomes(exchange, outcomes, pass, work.mesh.attributes.size());
  add_totals(totals, pass);
  std::vector<TilePiece> out;
  for (GroupOutcome& o : outcomes) {
    for (uint32_t id : o.freed) pending[id] = 0;
    out.push_back(std::move(o.piece));
  }
  // The triangles no group took, as they are.
  std::vector<uint32_t> rest;
  for (size_t t = 0; t < nt; ++t)
    if (group[t] == UINT32_MAX) rest.push_back(uint32_t(t));
  if (!rest.empty()) out.push_back(cut_piece(work.mesh, work.ids, nullptr, group, UINT32_MAX, rest));
  Work next;
  next.mesh = merge_pieces(out, work.mesh, &next.ids);
  return next;
}

// The triangles of work at a pending vertex, and `rings` rings of triangles around them.
std::vector<uint32_t> strip_triangles(const Work& work, const std::vector<uint8_t>& pending, int rings) {
  const Mesh& m = work.mesh;
  std::vector<uint8_t> near(m.vertex_count(), 0);
  for (size_t v = 0; v < m.vertex_count(); ++v) near[v] = pending[work.ids[v]];
  std::vector<uint8_t> taken(m.triangle_count(), 0);
  for (int r = 0; r <= rings; ++r) {
    for (size_t t = 0; t < m.triangle_count(); ++t) {
      const uint32_t* v = &m.triangles[3 * t];
      taken[t] |= near[v[0]] | near[v[1]] | near[v[2]];
    }
    for (size_t t = 0; t < m.triangle_count(); ++t)
      if (taken[t])
        for (int k = 0; k < 3; ++k) near[m.triangles[3 * t + k]] = 1;
  }
  std::vector<uint32_t> list;
  for (size_t t = 0; t < m.triangle_count(); ++t)
    if (taken[t]) list.push_back(uint32_t(t));
  return list;
}

// The passes over the mesh in memory, for run_rounds.
class MemoryPasses final : public TilePasses {
 public:
  MemoryPasses(Work& work, const std::vector<double>* weights, const SimplifyOptions& options,
               std::vector<uint8_t>& pending, PassTotals& totals)
      : work_(work), weights_(weights), options_(options), pending_(pending), totals_(totals) {}
  uint64_t triangles() const override { return work_.mesh.triangle_count(); }
  void first_pass(const TileGrid& grid, const PassBudget& budget) override {
    std::vector<uint32_t> all(work_.mesh.triangle_count());
    for (size_t t = 0; t < all.size(); ++t) all[t] = uint32_t(t);
    std::fill(pending_.begin(), pending_.end(), 1);  // every vertex waits for the round's first pass
    work_ = run_pass(work_, all, grid, budget, weights_, options_, pending_, totals_);
  }
  bool strip_pass(const TileGrid& grid, const PassBudget& budget) override {
    const std::vector<uint32_t> strips = strip_triangles(work_, pending_, kStripRings);
    if (strips.empty()) return false;
    work_ = run_pass(work_, strips, grid, budget, weights_, options_, pending_, totals_);
    return true;
  }

 private:
  Work& work_;
  const std::vector<double>* weights_;
  const SimplifyOptions& options_;
  std::vector<uint8_t>& pending_;
  PassTotals& totals_;
};

}  // namespace

Simplified simplify_mesh_tiled(const Mesh& mesh, const SimplifyOptions& options,
                               const std::vector<double>& weights) {
  const unsigned tiles = options.tiles;
  if (tiles <= 1 || simplify_keeps_mesh(options, mesh.triangle_count())) {
    SimplifyOptions whole = options;
    whole.tiles = 0;
    return simplify_mesh(mesh, whole, weights);
  }
  const std::vector<double>* vertex_weights = weights.empty() ? nullptr : &weights;
  if (tiles > kMaxSimplifyTiles)
    throw Error("simplify: at most " + std::to_string(kMaxSimplifyTiles) + " tiles along the longest axis, got " +
                std::to_string(tiles));
  if (options.target_error > 0)
    throw Error("simplify: tiled simplification takes a face target (target_faces or ratio), not target_error");
  if (!mesh.position_vertex.empty())
    throw Error("simplify: tiled simplification does not take a mesh split at seams (position_vertex)");
  if (options.record_collapses) throw Error("simplify: tiled simplification does not record the collapses");
  const CancelScope cancel(options.cancel);
  const Timer t0;
  const size_t nv = mesh.vertex_count();
  if (vertex_weights) {
    if (vertex_weights->size() != nv)
      throw Error("simplify: " + std::to_string(vertex_weights->size()) + " vertex weights for a mesh of " +
                  std::to_string(nv) + " vertices");
    for (double x : *vertex_weights)
      if (!(x >= 0) || !std::isfinite(x)) throw Error("simplify: vertex weights must be finite and >= 0");
  }
  if (!mesh.triangle_material.empty() && mesh.triangle_material.size() != mesh.triangle_count())
    throw Error("simplify: triangle_material has " + std::to_string(mesh.triangle_material.size()) +
                " entries for " + std::to_string(mesh.triangle_count()) + " triangles");
  for (size_t i = 0; i < mesh.triangles.size(); ++i)
    if (mesh.triangles[i] >= nv)
      throw Error("simplify: triangle " + std::to_string(i / 3) + " has a vertex index out of range");
  Work work;
  work.mesh.positions = mesh.positions;
  work.mesh.attributes = mesh.attributes;
  copy_mesh_context(mesh, work.mesh);
  // As simplify_mesh: triangles with a repeated index are not part of the surface.
  for (size_t t = 0; t < mesh.triangle_count(); ++t) {
    const uint32_t* v = &mesh.triangles[3 * t];
    if (v[0] == v[1] || v[1] == v[2] || v[0] == v[2]) continue;
    work.mesh.triangles.insert(work.mesh.triangles.end(), v, v + 3);
    if (!mesh.triangle_material.empty()) work.mesh.triangle_material.push_back(mesh.triangle_material[t]);
  }
  const size_t faces = work.mesh.triangle_count();
  const size_t target = resolve_target_faces(options, faces);
  const std::vector<uint8_t> used = referenced_vertices(mesh);
  const BoundingBox box = bounding_box(mesh.positions.data(), nv, used.data());
  for (size_t v = 0; v < nv; ++v)
    for (int k = 0; k < 3; ++k)
      if (used[v] && !std::isfinite(mesh.positions[3 * v + k]))
        throw Error("simplify: vertex " + std::to_string(v) + " is not finite");

  // (work.mesh has no source positions: the frame is carried from `mesh` at the end.)
  work.ids.resize(nv);
  for (size_t v = 0; v < nv; ++v) work.ids[v] = uint32_t(v);
  PassTotals totals;
  std::vector<uint8_t> pending(nv);
  MemoryPasses passes(work, vertex_weights, options, pending, totals);
  run_rounds(passes, box, tiles, target);

  Simplified r;
  r.mesh = std::move(work.mesh);
  carry_model_frame(mesh, work.ids, r.mesh);  // an unmoved vertex is written as it was read
  SimplifyReport& report = r.report;
  report.input_faces = faces;
  report.target_faces = target;
  report.output_faces = r.mesh.triangle_count();
  report.output_vertices = r.mesh.vertex_count();
  report.reached = report.output_faces == target;
  report.warning = precision_warning(mesh);
  if (!report.reached)
    report.note = "tiled simplification stopped at " + std::to_string(report.output_faces) + " faces (target " +
                  std::to_string(target) + "): the strips along the tile cuts could not give up more";
  report.collapses = totals.collapses;
  report.refused = totals.refused;
  report.error = box.diagonal() > 0 ? totals.error / box.diagonal() : 0;
  report.vertex_origin = std::move(work.ids);
  report.seconds = t0.seconds();
  return r;
}

}  // namespace meshsal
