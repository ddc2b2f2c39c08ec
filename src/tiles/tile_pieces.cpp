// meshsal (internal): cutting and joining the pieces of tiled simplification, see
// tile_pieces.h.
#include "tiles/tile_pieces.h"

#include <algorithm>
#include <string>
#include <utility>

#include "core/id_ranks.h"
#include "core/mesh_context.h"
#include "simplify/simplify.h"

namespace meshsal {
namespace detail {

VertexTriangles vertex_triangles(const Mesh& mesh) {
  VertexTriangles r;
  r.start.assign(mesh.vertex_count() + 1, 0);
  for (uint32_t v : mesh.triangles) ++r.start[v + 1];
  for (size_t v = 0; v < mesh.vertex_count(); ++v) r.start[v + 1] += r.start[v];
  r.tri.resize(mesh.triangles.size());
  std::vector<uint32_t> fill(r.start.begin(), r.start.end() - 1);
  for (size_t i = 0; i < mesh.triangles.size(); ++i) r.tri[fill[mesh.triangles[i]]++] = uint32_t(i / 3);
  return r;
}

namespace {

// `out` = the triangles `list` of `mesh` over the vertices `verts` (increasing), with
// their per-vertex data; local[3 * i + k] is the position in verts of list[i]'s corner k.
// The caller sets the ids.
void copy_submesh(const Mesh& mesh, const std::vector<uint32_t>& verts, const std::vector<uint32_t>& list,
                  const std::vector<uint32_t>& local, Mesh& out) {
  out.positions.resize(3 * verts.size());
  for (size_t i = 0; i < verts.size(); ++i)
    for (int k = 0; k < 3; ++k) out.positions[3 * i + k] = mesh.positions[3 * size_t(verts[i]) + k];
  for (const VertexAttribute& a : mesh.attributes) {
    VertexAttribute b{a.name, std::vector<float>(verts.size())};
    for (size_t i = 0; i < verts.size(); ++i) b.values[i] = a.values[verts[i]];
    out.attributes.push_back(std::move(b));
  }
  out.triangles = local;
  if (!mesh.triangle_material.empty())
    for (uint32_t t : list) out.triangle_material.push_back(mesh.triangle_material[t]);
  copy_mesh_context(mesh, out);
}

// The corners of the triangles `list` of `mesh`, triangle by triangle.
std::vector<uint32_t> corners_of(const Mesh& mesh, const std::vector<uint32_t>& list) {
  std::vector<uint32_t> corners(3 * list.size());
  for (size_t i = 0; i < list.size(); ++i)
    for (int k = 0; k < 3; ++k) corners[3 * i + k] = mesh.triangles[3 * size_t(list[i]) + k];
  return corners;
}

uint32_t max_vertex(const Mesh& mesh) { return uint32_t(mesh.vertex_count() > 0 ? mesh.vertex_count() - 1 : 0); }

}  // namespace

TilePiece cut_piece(const Mesh& mesh, const std::vector<uint32_t>& ids, const VertexTriangles* around,
                    const std::vector<uint32_t>& group, uint32_t group_id, const std::vector<uint32_t>& tile) {
  std::vector<uint32_t> verts, local, guards;
  if (around) {
    const std::vector<uint32_t> corners = corners_of(mesh, tile);
    rank_ids(corners.data(), corners.size(), max_vertex(mesh), verts, local);
    for (uint32_t v : verts)
      for (uint32_t i = around->start[v]; i < around->start[v + 1]; ++i)
        if (group[around->tri[i]] != group_id) guards.push_back(around->tri[i]);
  }
  std::sort(guards.begin(), guards.end());
  guards.erase(std::unique(guards.begin(), guards.end()), guards.end());
  std::vector<uint32_t> list = tile;
  list.insert(list.end(), guards.begin(), guards.end());
  const std::vector<uint32_t> corners = corners_of(mesh, list);
  rank_ids(corners.data(), corners.size(), max_vertex(mesh), verts, local);
  TilePiece p;
  copy_submesh(mesh, verts, list, local, p.mesh);
  p.ids.resize(verts.size());
  for (size_t i = 0; i < verts.size(); ++i) p.ids[i] = ids[verts[i]];
  p.pinned.assign(verts.size(), 0);
  for (size_t i = 3 * tile.size(); i < p.mesh.triangles.size(); ++i) p.pinned[p.mesh.triangles[i]] = 1;
  p.guards = guards.size();
  return p;
}

TilePiece simplify_tile(const TilePiece& tile, const std::vector<double>* weights, size_t target_faces,
                        const SimplifyOptions& options, SimplifyReport* report, bool record) {
  SimplifyOptions o = options;
  o.target_faces = target_faces + tile.guards;
  o.ratio = 0;
  o.target_error = 0;
  o.record_collapses = record;
  // Open borders move as options.lock_border says. (They were kept in place until every
  // pass took its goals from the common error level: a strip piece of five triangles at a
  // corner of a plane, told to give up one, gave up the corner.)
  o.lock_border = options.lock_border;
  SimplifyReport rep;
  const Mesh out = simplify_pinned(tile.mesh, o, weights, &tile.pinned, &rep);
  const std::vector<uint32_t>& from = rep.vertex_origin;  // output vertex -> tile vertex
  // Collapses keep the triangle order and never touch a guard: they are the last ones.
  const size_t own = out.triangle_count() - tile.guards;
  for (size_t i = 0; i < 3 * tile.guards; ++i)
    if (from[out.triangles[3 * own + i]] != tile.mesh.triangles[tile.mesh.triangles.size() - 3 * tile.guards + i])
      throw Error("simplify: internal error: a tile changed a triangle outside it");
  // Keep the vertices the tile's own triangles use.
  std::vector<uint32_t> keep(out.vertex_count(), UINT32_MAX), verts;
  for (size_t i = 0; i < 3 * own; ++i) keep[out.triangles[i]] = 0;
  for (size_t v = 0; v < keep.size(); ++v)
    if (keep[v] == 0) {
      keep[v] = uint32_t(verts.size());
      verts.push_back(uint32_t(v));
    }
  TilePiece r;
  std::vector<uint32_t> list(own), local(3 * own);
  for (size_t t = 0; t < own; ++t) list[t] = uint32_t(t);
  for (size_t i = 0; i < 3 * own; ++i) local[i] = keep[out.triangles[i]];
  copy_submesh(out, verts, list, local, r.mesh);
  r.ids.resize(verts.size());
  r.pinned.resize(verts.size());
  for (size_t i = 0; i < verts.size(); ++i) {
    const uint32_t v = from[verts[i]];
    r.ids[i] = tile.ids[v];
    r.pinned[i] = tile.pinned[v];
    // A pinned vertex that took a collapse went through the simplifier's internal frame and
    // back (its attributes through the carrier); its neighbour tiles have it as it was
    // read: take that, to the bit, so every piece (and every pass) agrees on it.
    if (tile.pinned[v]) {
      for (int k = 0; k < 3; ++k) r.mesh.positions[3 * i + k] = tile.mesh.positions[3 * size_t(v) + k];
      for (size_t a = 0; a < r.mesh.attributes.size(); ++a)
        r.mesh.attributes[a].values[i] = tile.mesh.attributes[a].values[v];
    }
  }
  if (report) *report = std::move(rep);
  return r;
}

Mesh merge_pieces(const std::vector<TilePiece>& pieces, const Mesh& like, std::vector<uint32_t>* ids) {
  // (global id, piece, vertex) for every vertex of every piece; the first of each id wins.
  struct Source {
    uint32_t id, piece, vertex;
  };
  std::vector<Source> all;
  for (size_t p = 0; p < pieces.size(); ++p) {
    if (pieces[p].guards != 0) throw Error("simplify: internal error: merging a piece with guards");
    for (size_t v = 0; v < pieces[p].ids.size(); ++v) all.push_back({pieces[p].ids[v], uint32_t(p), uint32_t(v)});
  }
  std::stable_sort(all.begin(), all.end(), [](const Source& a, const Source& b) { return a.id < b.id; });
  Mesh out;
  copy_mesh_context(like, out);
  for (const VertexAttribute& a : like.attributes) out.attributes.push_back({a.name, {}});
  std::vector<std::vector<uint32_t>> index(pieces.size());
  for (size_t p = 0; p < pieces.size(); ++p) index[p].resize(pieces[p].ids.size());
  ids->clear();
  for (const Source& s : all) {
    const Mesh& m = pieces[s.piece].mesh;
    if (ids->empty() || ids->back() != s.id) {
      ids->push_back(s.id);
      for (int k = 0; k < 3; ++k) out.positions.push_back(m.positions[3 * size_t(s.vertex) + k]);
      for (size_t a = 0; a < out.attributes.size(); ++a) out.attributes[a].values.push_back(m.attributes[a].values[s.vertex]);
    }
    index[s.piece][s.vertex] = uint32_t(ids->size() - 1);
  }
  const bool materials = !like.triangle_material.empty();
  for (size_t p = 0; p < pieces.size(); ++p) {
    for (uint32_t v : pieces[p].mesh.triangles) out.triangles.push_back(index[p][v]);
    if (materials)
      out.triangle_material.insert(out.triangle_material.end(), pieces[p].mesh.triangle_material.begin(),
                                   pieces[p].mesh.triangle_material.end());
  }
  return out;
}

}  // namespace detail
}  // namespace meshsal
