// meshsal: Garland-Heckbert edge-collapse simplification over flat arrays.
// One shared state (positions, quadrics, vertex -> triangle lists) with two ways to pick
// the next collapse: a lazily invalidated queue of edges (simplify_mesh) and a full scan
// (simplify_bruteforce, the test oracle). Both use the same cost, check and collapse code.
#include "core/model_frame.h"
#include "simplify/simplify.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cmath>
#include <cstring>
#include <new>
#include <string>

#include "meshsal/meshsal.h"
#include "core/cancel.h"
#include "core/parallel.h"
#include "simplify/edge_queue.h"
#include "simplify/quadric.h"
#include "core/timer.h"

namespace meshsal {

size_t resolve_target_faces(const SimplifyOptions& options, size_t input_faces) {
  if (input_faces == 0) throw Error("simplify: the mesh has no non-degenerate triangles");
  size_t target = options.target_faces;
  if (!(options.target_error >= 0 && options.target_error <= 1))
    throw Error("simplify: target error must be in [0, 1] (a fraction of the bounding-box diagonal), got " +
                std::to_string(options.target_error));
  if (target == 0 && options.ratio == 0 && options.target_error > 0) return 1;
  if (target == 0) {
    const double r = options.ratio;
    if (r == 0)
      throw Error("simplify: give a target face count (> 0) or a ratio in (0, 1]");
    if (!(r > 0 && r <= 1))
      throw Error("simplify: ratio must be in (0, 1], got " + std::to_string(r));
    target = static_cast<size_t>(std::llround(r * static_cast<double>(input_faces)));
    if (target == 0)
      throw Error("simplify: ratio " + std::to_string(r) + " leaves no faces of " +
                  std::to_string(input_faces));
  }
  if (target > input_faces)
    throw Error("simplify: target of " + std::to_string(target) +
                " faces is larger than the mesh (" + std::to_string(input_faces) + " faces)");
  return target;
}

using namespace simplify_detail;

namespace {

enum class Check { Ok, NotEdge, Refused };

// Branch-free helpers for the hot loops below, where the outcome is a coin toss (GCC turns
// the obvious ternaries into jumps there).
inline uint32_t select_u32(bool c, uint32_t x, uint32_t y) {  // c ? x : y
  const uint32_t m = 0u - uint32_t(c);
  return (x & m) | (y & ~m);
}
// Triangle v (three corners) and one of its corners c: is c a corner of it, and which are
// the other two (in an order that is not the triangle's orientation).
inline bool has_corner(const uint32_t* v, uint32_t c) {
  return (v[0] == c) | (v[1] == c) | (v[2] == c);
}
inline void other_corners(const uint32_t* v, uint32_t c, uint32_t* x, uint32_t* y) {
  *x = select_u32(v[0] == c, v[1], v[0]);
  *y = select_u32(v[2] == c, v[1], v[2]);
}

// The 10 low bits of x spread out to every third bit (bit i to bit 3i): interleaving three
// of them gives a 30-bit Morton code.
inline uint32_t spread_bits(uint32_t x) {
  x &= 0x3ffu;
  x = (x | (x << 16)) & 0x030000ffu;
  x = (x | (x << 8)) & 0x0300f00fu;
  x = (x | (x << 4)) & 0x030c30c3u;
  x = (x | (x << 2)) & 0x09249249u;
  return x;
}

inline void cross3(const double u[3], const double v[3], double o[3]) {
  o[0] = u[1] * v[2] - u[2] * v[1];
  o[1] = u[2] * v[0] - u[0] * v[2];
  o[2] = u[0] * v[1] - u[1] * v[0];
}
inline double dot3(const double u[3], const double v[3]) {
  return u[0] * v[0] + u[1] * v[1] + u[2] * v[2];
}

struct State {
  size_t nv = 0;
  double center[3] = {0, 0, 0};
  double scale = 1;                          // internal = (p - center) * scale
  // The input's positions (3 per input vertex): a vertex no collapse moved is written back
  // with these exact values, not through the rounding of (p - center) * scale and back.
  const float* input_positions = nullptr;
  // What a collapse reads of each vertex around it, in two cache lines of one record
  // (instead of a miss in each of three arrays).
  struct alignas(64) Vertex {
    Quadric q;
    // Sum of the plane weights in q (triangle areas, border weights, times W): the
    // collapse error sqrt(Q(v) / weight) is a distance (target_error).
    double plane_weight;
    double p[3];  // internal coordinates
  };
  std::vector<Vertex> vert;
  double max_error2 = HUGE_VAL;              // target_error squared (internal units)
  double reached_error2 = 0;                 // largest squared error of a collapse made
  size_t error_refused = 0;                  // refusals for the error bound
  // Locked vertices (seam twins, lock_border) neither move nor go.
  std::vector<uint8_t> locked;
  bool has_locks = false;
  // Seam twins: twin_next[v] is the next vertex of v's position group (a cycle), NONE
  // outside groups; pos_group[v] names v's group (a member's id; v itself outside groups).
  static constexpr uint32_t NONE = UINT32_MAX;
  std::vector<uint32_t> twin_next, pos_group, weld_mark;
  // A seam vertex whose group has two members (one each side) has a partner: a seam edge
  // between two such vertices collapses on both sides at once, along the seam.
  std::vector<uint32_t> partner;
  bool pair(uint32_t v) const { return !partner.empty() && partner[v] != NONE; }
  bool seam_edge(uint32_t a, uint32_t b) const { return pair(a) && pair(b); }
  bool seam_mode = false;  // check() runs for one side of a seam edge
  // 1 for a twin and (at least) every vertex next to one: only their collapses need the
  // welded link condition (elsewhere the split one is the same). Kept by collapse().
  std::vector<uint8_t> near_seam;
  double seam_cost(uint32_t a, uint32_t b, double out[3]) const {
    if (!seam_edge(a, b)) return HUGE_VAL;
    const Quadric q = vert[a].q + vert[partner[a]].q + vert[b].q + vert[partner[b]].q;
    const double ea = q.error(p(a)), eb = q.error(p(b));
    const double* k = eb < ea ? p(b) : p(a);  // the cheaper end stays, on both sides
    for (int i = 0; i < 3; ++i) out[i] = k[i];
    return std::min(ea, eb);
  }
  Check check_edge(uint32_t a, uint32_t b, const double np[3]);
  uint32_t weld_stamp = 0;
  bool has_twins = false;
  // The link condition on the welded surface (seams closed): merging b's position group
  // into a's, their only common welded neighbours are the `expected` opposites (k, or one
  // each side along a seam), and no other twin of one end neighbours the other end.
  bool welded_link_ok(uint32_t a, uint32_t b, size_t expected, bool along_seam);
  // Attributes: `nattr` floats per internal vertex; nx ny nz at normal_at (-1: none).
  size_t nattr = 0;
  std::vector<float> attr;
  int normal_at[3] = {-1, -1, -1};
  std::vector<uint32_t> tri;                 // 3 per triangle
  std::vector<uint8_t> tri_alive;
  std::vector<uint32_t> tri_material;        // per triangle when the input has triangle_material
  // Triangles of each vertex (may hold dead ones): runs in one pool, run_of[v].count
  // entries from run_of[v].start, room for run_of[v].cap; a run that outgrows its room
  // moves to the end.
  struct alignas(16) RunPlace {  // one record: one miss per vertex, not three
    uint32_t start, count, cap;
  };
  std::vector<uint32_t> vt_pool;
  std::vector<RunPlace> run_of;
  struct Run {
    const uint32_t* b;
    const uint32_t* e;
    const uint32_t* begin() const { return b; }
    const uint32_t* end() const { return e; }
  };
  uint32_t* tris_of(uint32_t v) { return vt_pool.data() + run_of[v].start; }
  const uint32_t* tris_of(uint32_t v) const { return vt_pool.data() + run_of[v].start; }
  Run vt(uint32_t v) const { return {tris_of(v), tris_of(v) + run_of[v].count}; }
  // Lays all runs out again in vertex order, live triangles only, each with room for half
  // as many more: instead of growing the pool (a copy of all of it, and page faults), and it
  // puts the runs back in Morton order.
  void repack() {
    std::vector<uint32_t> fresh;
    fresh.reserve(vt_pool.capacity());
    for (size_t v = 0; v < nv; ++v) {
      const uint32_t start = uint32_t(fresh.size());
      if (alive[v])
        for (uint32_t t : vt(uint32_t(v)))
          if (tri_alive[t]) fresh.push_back(t);
      run_of[v].start = start;
      run_of[v].count = uint32_t(fresh.size()) - start;
      run_of[v].cap = run_of[v].count + run_of[v].count / 2;
      fresh.resize(start + run_of[v].cap);
    }
    vt_pool.swap(fresh);
  }
  // Drops the dead triangles from v's run.
  void compact(uint32_t v) {
    const auto live = [&](uint32_t t) { return tri_alive[t] != 0; };
    run_of[v].count = uint32_t(keep_if(tris_of(v), run_of[v].count, live));
  }
  std::vector<uint8_t> alive;
  std::vector<uint8_t> border;               // on an open border or a non-manifold edge
  size_t border_vertices = 0;                // live vertices with border[] set
  // Collapse count when the vertex last moved; UINT32_MAX once it is collapsed away, so
  // that one 4-byte load per end tells whether an entry is current.
  std::vector<uint32_t> changed;
  std::vector<uint32_t> order;               // internal vertex id -> input vertex
  std::vector<uint32_t> inv;                 // input vertex -> internal id
  size_t faces = 0;
  size_t target = 0;
  double min_cos = 0;
  size_t refused = 0;
  std::vector<Collapse> sequence;
  bool record = false;
  // scratch
  std::vector<uint32_t> opp, flip_a, flip_b;  // sized to the largest fan seen
  // Per vertex: marks for the link condition (check) and the new ring (after a collapse),
  // one array for both so that the ring's marks are still in cache; each use takes fresh
  // stamp values, so nothing is ever cleared.
  std::vector<uint32_t> mark;
  uint32_t stamp = 0;
  // n fresh stamp values; returns the last. Starts over (all marks cleared) before the
  // counter would wrap.
  uint32_t new_stamps(uint32_t n) {
    if (stamp > UINT32_MAX - n) {
      std::fill(mark.begin(), mark.end(), 0);
      stamp = 0;
    }
    return stamp += n;
  }

  const double* p(uint32_t v) const { return vert[v].p; }

  double cost(uint32_t a, uint32_t b, double out[3]) const {
    if (has_locks && (locked[a] | locked[b])) {  // the new vertex stays where the locked one is
      if (locked[a] && locked[b]) return seam_cost(a, b, out);
      const double* k = p(locked[a] ? a : b);
      for (int i = 0; i < 3; ++i) out[i] = k[i];
      return (vert[a].q + vert[b].q).error(k);
    }
    return optimal_placement(vert[a].q + vert[b].q, p(a), p(b), out);
  }
  // No collapse can join two locked vertices: such edges never enter the queue.
  bool both_locked(uint32_t a, uint32_t b) const {
    return has_locks && locked[a] && locked[b] && !seam_edge(a, b);
  }
  // With vertex weights: each vertex's unweighted quadric and plane weight, for error2.
  struct Plain {
    Quadric q;
    double plane_weight;
    Plain& operator+=(const Plain& o) {
      q += o.q;
      plane_weight += o.plane_weight;
      return *this;
    }
  };
  std::vector<Plain> plain;
  // The collapse's error squared (see SimplifyOptions::target_error): a distance, so with
  // vertex weights it is taken from the unweighted quadrics (a weight near 0 would hide
  // what a collapse costs: a flat region's border cut away read as error 0).
  double error2(uint32_t a, uint32_t b, const double np[3], double cost) const {
    if (plain.empty()) {
      double w = vert[a].plane_weight + vert[b].plane_weight;
      if (seam_edge(a, b)) w += vert[partner[a]].plane_weight + vert[partner[b]].plane_weight;
      return w > 0 ? cost / w : 0;
    }
    Plain sum = plain[a];
    sum += plain[b];
    if (seam_edge(a, b)) sum += plain[partner[a]], sum += plain[partner[b]];
    return sum.plane_weight > 0 ? std::max(0.0, sum.q.error(np)) / sum.plane_weight : 0;
  }
  // Refuses a collapse over the error bound (before the costlier check()).
  bool over_error(uint32_t a, uint32_t b, const double np[3], double cost) {
    if (!(error2(a, b, np, cost) > max_error2)) return false;
    ++error_refused;
    return true;
  }
  // check() passed: collapses the edge onto its locked end if it has one, else onto a.
  // Returns how many collapses it made (2 along a seam); kept[i] took removed[i].
  int apply(uint32_t a, uint32_t b, const double np[3], double cost, uint32_t kept[2], uint32_t removed[2]) {
    reached_error2 = std::max(reached_error2, error2(a, b, np, cost));
    if (seam_edge(a, b)) {
      const double* pb = p(b);
      if (np[0] == pb[0] && np[1] == pb[1] && np[2] == pb[2]) std::swap(a, b);  // b's end stays
      kept[0] = a, removed[0] = b, kept[1] = partner[a], removed[1] = partner[b];
      collapse(a, b, np, cost);
      collapse(kept[1], removed[1], np, cost);
      return 2;
    }
    if (has_locks && locked[b]) std::swap(a, b);
    kept[0] = a, removed[0] = b;
    collapse(a, b, np, cost);
    return 1;
  }

  // Setup, in this order (init calls them): the input checked and its degenerate
  // triangles dropped; vertices renumbered along a Morton curve in internal coordinates;
  // each vertex's triangle run and plane quadrics; the unique edges with the border
  // quadrics; then the weights and the initial edge costs.
  void init(const Mesh& mesh, const SimplifyOptions& options, const std::vector<double>* w,
            std::vector<Entry>* edges);
  void take_input(const Mesh& mesh, const SimplifyOptions& options, const std::vector<double>* w);
  void take_locks_and_attributes(const Mesh& mesh, bool lock_border);
  void order_vertices(const Mesh& mesh);
  void build_triangle_runs();
  void build_edges(double border_weight, std::vector<uint32_t>* edge_a, std::vector<uint32_t>* edge_b);
  Check check(uint32_t a, uint32_t b, const double np[3]);
  // Would triangle t, with vertex `moved` placed at np, flip, fold or degenerate?
  bool bad_triangle(uint32_t t, uint32_t moved, const double np[3]) const;
  void collapse(uint32_t a, uint32_t b, const double np[3], double cost);
  // An entry is current while neither end has changed (or died) since its cost was
  // computed. & not &&: no branches, it runs over whole buckets.
  bool current(const Entry& e) const {
    return (changed[e.a] <= e.stamp) & (changed[e.b] <= e.stamp);
  }
  size_t collapses = 0;
  const Mesh* mesh_in = nullptr;
  Mesh output(SimplifyReport* report) const;
  void output_attributes(const Mesh& in, const std::vector<uint32_t>& origin, Mesh* out) const;
};

void State::init(const Mesh& mesh, const SimplifyOptions& options, const std::vector<double>* w,
                 std::vector<Entry>* edges) {
  take_input(mesh, options, w);
  order_vertices(mesh);
  build_triangle_runs();
  std::vector<uint32_t> unique_edges_a, unique_edges_b;
  build_edges(options.border_weight, &unique_edges_a, &unique_edges_b);
  if (w) {
    plain.resize(nv);
    for (size_t v = 0; v < nv; ++v) plain[v] = {vert[v].q, vert[v].plane_weight};
  }
  if (w)
    for (size_t v = 0; v < nv; ++v) {
      vert[v].q *= (*w)[order[v]];
      vert[v].plane_weight *= (*w)[order[v]];
    }
  if (options.target_error > 0) max_error2 = options.target_error * options.target_error;
  take_locks_and_attributes(mesh, options.lock_border);
  changed.assign(nv, 0);
  mark.assign(nv, 0);
  for (size_t v = 0; v < nv; ++v) border_vertices += alive[v] && border[v];

  if (edges) {
    edges->resize(unique_edges_a.size());
    // Independent per edge: on all cores (a tenth of the whole run on one).
    parallel_for(unique_edges_a.size(), options.threads, 8192, [&](size_t begin, size_t end) {
      double tmp[3];
      for (size_t i = begin; i < end; ++i) {
        const uint32_t a = unique_edges_a[i], b = unique_edges_b[i];
        (*edges)[i] = make_entry(cost(a, b, tmp), a, b, 0);
      }
    });
  }
}

void State::take_input(const Mesh& mesh, const SimplifyOptions& options,
                       const std::vector<double>* w) {
  mesh_in = &mesh;
  nv = mesh.vertex_count();
  input_positions = mesh.positions.data();
  const size_t nt_in = mesh.triangle_count();
  for (size_t i = 0; i < mesh.triangles.size(); ++i)
    if (mesh.triangles[i] >= nv)
      throw Error("simplify: triangle " + std::to_string(i / 3) + " has a vertex index out of range");
  if (w) {
    if (w->size() != nv)
      throw Error("simplify: " + std::to_string(w->size()) + " vertex weights for a mesh of " +
                  std::to_string(nv) + " vertices");
    for (double x : *w)
      if (!(x >= 0) || !std::isfinite(x))
        throw Error("simplify: vertex weights must be finite and >= 0");
  }
  // Triangles with a repeated index are not part of the surface: drop them.
  // Each kept triangle's material goes with it (a collapse never changes it).
  const bool materials = !mesh.triangle_material.empty();
  if (materials && mesh.triangle_material.size() != nt_in)
    throw Error("simplify: triangle_material has " + std::to_string(mesh.triangle_material.size()) +
                " entries for " + std::to_string(nt_in) + " triangles");
  tri.reserve(3 * nt_in);
  for (size_t t = 0; t < nt_in; ++t) {
    const uint32_t* v = &mesh.triangles[3 * t];
    if (v[0] == v[1] || v[1] == v[2] || v[0] == v[2]) continue;
    tri.insert(tri.end(), v, v + 3);
    if (materials) tri_material.push_back(mesh.triangle_material[t]);
  }
  const size_t nt = tri.size() / 3;
  faces = nt;
  target = resolve_target_faces(options, nt);
  min_cos = options.min_normal_cos;
  record = options.record_collapses;
}

void State::take_locks_and_attributes(const Mesh& mesh, bool lock_border) {
  locked.assign(nv, 0);
  if (lock_border)
    for (size_t v = 0; v < nv; ++v) locked[v] = border[v];
  const std::vector<uint32_t>& pv = mesh.position_vertex;
  if (!pv.empty()) {
    if (pv.size() != nv) throw Error("simplify: position_vertex does not have one entry per vertex");
    std::vector<uint32_t> group(nv, 0);
    for (size_t i = 0; i < nv; ++i) {
      if (pv[i] > i || pv[pv[i]] != pv[i])
        throw Error("simplify: position_vertex of vertex " + std::to_string(i) + " is not a lower vertex that stands for itself");
      ++group[pv[i]];
    }
    for (size_t i = 0; i < nv; ++i) locked[inv[i]] |= group[pv[i]] > 1;  // a seam twin
    twin_next.assign(nv, NONE);
    pos_group.resize(nv);
    std::vector<uint32_t> last(nv, NONE);  // per group (input id): the member linked last
    for (size_t i = 0; i < nv; ++i) {
      const uint32_t v = inv[i], r = pv[i];
      pos_group[v] = inv[r];
      if (group[r] < 2) continue;
      has_twins = true;
      if (last[r] == NONE) {
        twin_next[v] = v;
      } else {  // insert after the last one, closing the cycle through the first
        twin_next[v] = twin_next[last[r]];
        twin_next[last[r]] = v;
      }
      last[r] = v;
    }
    weld_mark.assign(nv, 0);
    near_seam.assign(nv, 0);
    for (size_t t = 0; t < tri.size(); t += 3)
      if (twin_next[tri[t]] != NONE || twin_next[tri[t + 1]] != NONE || twin_next[tri[t + 2]] != NONE)
        near_seam[tri[t]] = near_seam[tri[t + 1]] = near_seam[tri[t + 2]] = 1;
    if (!lock_border) {
      partner.assign(nv, NONE);
      for (size_t v = 0; v < nv; ++v)
        if (twin_next[v] != NONE && twin_next[twin_next[v]] == v && twin_next[v] != v) partner[v] = twin_next[v];
    }
  }
  for (uint8_t x : locked) has_locks |= x != 0;
  nattr = mesh.attributes.size();
  if (!nattr) return;
  attr.resize(nattr * nv);
  for (size_t i = 0; i < nattr; ++i) {
    const VertexAttribute& a = mesh.attributes[i];
    if (a.values.size() != nv)
      throw Error("simplify: attribute '" + a.name + "' has " + std::to_string(a.values.size()) +
                  " values for " + std::to_string(nv) + " vertices");
    for (size_t v = 0; v < nv; ++v) attr[nattr * v + i] = a.values[order[v]];
    const int k = a.name == "nx" ? 0 : a.name == "ny" ? 1 : a.name == "nz" ? 2 : -1;
    if (k >= 0 && normal_at[k] < 0) normal_at[k] = int(i);
  }
}

Check State::check_edge(uint32_t a, uint32_t b, const double np[3]) {
  if (!seam_edge(a, b)) return check(a, b, np);
  if (faces < target + 2) return Check::Refused;  // two collapses, one face each
  seam_mode = true;
  Check c = check(a, b, np);
  if (c == Check::Ok) c = check(partner[a], partner[b], np);
  seam_mode = false;
  if (c == Check::Ok && !welded_link_ok(a, b, 2, true)) c = Check::Refused;
  return c;
}

bool State::welded_link_ok(uint32_t a, uint32_t b, size_t expected, bool along_seam) {
  weld_stamp += 2;
  const uint32_t seen = weld_stamp, counted = weld_stamp + 1;
  const uint32_t ga = pos_group[a], gb = pos_group[b];
  // Calls f(member, corner) over the live triangles of v's group (v alone outside one).
  auto for_group = [&](uint32_t v, auto f) {
    uint32_t w = v;
    do {
      for (uint32_t t : vt(w))
        if (tri_alive[t])
          for (int c = 0; c < 3; ++c) f(w, tri[3 * size_t(t) + c]);
      w = twin_next[w] == NONE ? v : twin_next[w];
    } while (w != v);
  };
  bool ok = true;
  // The edge itself (and its twin along a seam) is the only contact between the groups.
  auto allowed_contact = [&](uint32_t w, uint32_t c, uint32_t self, uint32_t other) {
    return (w == self && c == other) || (along_seam && w == partner[self] && c == partner[other]);
  };
  for_group(b, [&](uint32_t w, uint32_t c) {
    const uint32_t g = pos_group[c];
    if (g == ga) ok &= allowed_contact(w, c, b, a);
    else if (g != gb) weld_mark[g] = seen;
  });
  size_t common = 0;
  for_group(a, [&](uint32_t w, uint32_t c) {
    const uint32_t g = pos_group[c];
    if (g == gb) ok &= allowed_contact(w, c, a, b);
    if (weld_mark[g] == seen) {
      weld_mark[g] = counted;
      ++common;
    }
  });
  return ok && common == expected;
}

void State::order_vertices(const Mesh& mesh) {
  // Internal coordinates: centred on the bounding box and scaled to unit diagonal, so that
  // the relative tolerances below mean the same on every mesh.
  alive.assign(nv, 0);
  for (uint32_t v : tri) alive[v] = 1;
  double lo[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
  for (size_t v = 0; v < nv; ++v) {
    if (!alive[v]) continue;
    for (int k = 0; k < 3; ++k) {
      const double x = mesh.positions[3 * v + k];
      if (!std::isfinite(x)) throw Error("simplify: vertex " + std::to_string(v) + " is not finite");
      lo[k] = std::min(lo[k], x);
      hi[k] = std::max(hi[k], x);
    }
  }
  const double diag = std::sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
                                (hi[2] - lo[2]) * (hi[2] - lo[2]));
  for (int k = 0; k < 3; ++k) center[k] = 0.5 * (lo[k] + hi[k]);
  scale = diag > 0 ? 1 / diag : 1;
  // Internal vertex ids follow a Morton curve, so that the vertices of one neighbourhood sit
  // close together in memory: the collapse order jumps around the mesh, and this keeps each
  // collapse on few cache lines. Unreferenced vertices go last.
  order.resize(nv);
  {
    std::vector<uint32_t> code(nv);
    const double inv_ext[3] = {hi[0] > lo[0] ? 1 / (hi[0] - lo[0]) : 0, hi[1] > lo[1] ? 1 / (hi[1] - lo[1]) : 0,
                               hi[2] > lo[2] ? 1 / (hi[2] - lo[2]) : 0};
    for (size_t v = 0; v < nv; ++v) {
      uint64_t c = 0;
      if (alive[v]) {
        uint32_t q[3];
        for (int k = 0; k < 3; ++k)
          q[k] = uint32_t(std::min(1.0, std::max(0.0, (mesh.positions[3 * v + k] - lo[k]) * inv_ext[k])) * 1023.0);
        c = (spread_bits(q[0]) << 2) | (spread_bits(q[1]) << 1) | spread_bits(q[2]);
      } else {
        c = uint64_t(1) << 30;  // after every 30-bit code
      }
      code[v] = uint32_t(c);
      order[v] = uint32_t(v);
    }
    // Stable LSD radix sort on the 31-bit codes (11 + 10 + 10 bits): the order a stable
    // comparison sort gives, several times faster.
    std::vector<uint32_t> tmp(nv), count;
    for (int shift : {0, 11, 21}) {
      const uint32_t buckets = shift == 0 ? 2048 : 1024, mask = buckets - 1;
      count.assign(buckets + 1, 0);
      for (uint32_t v : order) ++count[((code[v] >> shift) & mask) + 1];
      for (uint32_t i = 0; i < buckets; ++i) count[i + 1] += count[i];
      for (uint32_t v : order) tmp[count[(code[v] >> shift) & mask]++] = v;
      order.swap(tmp);
    }
  }
  inv.resize(nv);
  for (size_t i = 0; i < nv; ++i) inv[order[i]] = uint32_t(i);
  for (uint32_t& v : tri) v = inv[v];
  {
    std::vector<uint8_t> a2(nv);
    for (size_t i = 0; i < nv; ++i) a2[i] = alive[order[i]];
    alive.swap(a2);
  }
  vert.assign(nv, Vertex{});
  for (size_t i = 0; i < nv; ++i)
    for (int k = 0; k < 3; ++k)
      vert[i].p[k] = (mesh.positions[3 * size_t(order[i]) + k] - center[k]) * scale;
}

void State::build_triangle_runs() {
  const size_t nt = tri.size() / 3;
  tri_alive.assign(nt, 1);
  std::vector<uint32_t> deg(nv, 0);
  for (uint32_t v : tri) ++deg[v];
  run_of.assign(nv, RunPlace{0, 0, 0});
  {
    size_t off = 0;
    for (size_t v = 0; v < nv; ++v) { run_of[v].start = uint32_t(off); run_of[v].cap = deg[v]; off += deg[v]; }
    vt_pool.reserve(2 * off + 64);
    vt_pool.resize(off);
  }
  for (size_t t = 0; t < nt; ++t) {
    const uint32_t* v = &tri[3 * t];
    const Quadric q = triangle_quadric(p(v[0]), p(v[1]), p(v[2]));
    const double area = q.a00 + q.a11 + q.a22;  // the trace: area times |n|^2
    for (int k = 0; k < 3; ++k) {
      vt_pool[run_of[v[k]].start + run_of[v[k]].count++] = uint32_t(t);
      vert[v[k]].q += q;
      vert[v[k]].plane_weight += area;
    }
  }
}

void State::build_edges(double border_weight, std::vector<uint32_t>* edge_a,
                        std::vector<uint32_t>* edge_b) {
  // Edges from the triangle runs: for each vertex a, its higher neighbours b, with the
  // number of triangles on (a, b) counted in per-vertex scratch (stamped with a, so nothing
  // is cleared between vertices). One triangle is a border edge, more than two a
  // non-manifold edge. Border quadrics are added in the order of (a, b), as a sort of all
  // edges would give. No branches in the fan loop: vertices are in Morton order, so the
  // scratch entries of a's neighbours are close in memory, and which of them was seen
  // before is a coin toss.
  border.assign(nv, 0);
  std::vector<uint32_t>& unique_edges_a = *edge_a;
  std::vector<uint32_t>& unique_edges_b = *edge_b;
  const size_t nt = tri.size() / 3;
  unique_edges_a.reserve(nt * 3 / 2 + 16);
  unique_edges_b.reserve(nt * 3 / 2 + 16);
  // Per neighbour u of a: the vertex a it was last seen from, the triangles on (a, u), and
  // the last of them with the corner where the edge starts: one record, one cache line.
  struct Seen {
    uint32_t from, count, tri, corner;
  };
  std::vector<Seen> seen(nv, Seen{UINT32_MAX, 0, 0, 0});
  std::vector<uint32_t> higher, border_b;
  for (uint32_t a = 0; a < nv; ++a) {
    const uint32_t deg_a = run_of[a].count;
    if (higher.size() < 2 * size_t(deg_a)) higher.resize(2 * size_t(deg_a));
    size_t n = 0;
    for (uint32_t t : vt(a)) {
      const uint32_t* v = &tri[3 * size_t(t)];
      const uint32_t k = uint32_t(v[1] == a) + 2 * uint32_t(v[2] == a);
      const uint32_t u1 = v[(k + 1) % 3], u2 = v[(k + 2) % 3];
      // edge a -> u1 starts at corner k, edge u2 -> a at corner k + 2
      const uint32_t corner[2] = {k, (k + 2) % 3};
      const uint32_t ends[2] = {u1, u2};
      for (int e = 0; e < 2; ++e) {
        const uint32_t u = ends[e];
        Seen& s = seen[u];
        const bool fresh = s.from != a;
        s.from = a;
        s.count = fresh ? 1 : s.count + 1;
        s.tri = t;  // the triangle of a border edge (read only when it is the one)
        s.corner = corner[e];
        higher[n] = u;
        n += fresh & (u > a);
      }
    }
    border_b.clear();
    for (size_t i = 0; i < n; ++i) {
      const uint32_t b = higher[i], c = seen[b].count;
      if (c == 1) border_b.push_back(b);
      if (c > 2) border[a] = border[b] = 1;
      unique_edges_a.push_back(a);
      unique_edges_b.push_back(b);
    }
    std::sort(border_b.begin(), border_b.end());
    for (uint32_t b : border_b) {
      const uint32_t t = seen[b].tri, k = seen[b].corner;
      const uint32_t v0 = tri[3 * t + k], v1 = tri[3 * t + (k + 1) % 3], v2 = tri[3 * t + (k + 2) % 3];
      const Quadric q = border_quadric(p(v0), p(v1), p(v2), border_weight);
      vert[v0].q += q;
      vert[v1].q += q;
      vert[v0].plane_weight += q.a00 + q.a11 + q.a22;
      vert[v1].plane_weight += q.a00 + q.a11 + q.a22;
      border[a] = border[b] = 1;
    }
  }
}

bool State::bad_triangle(uint32_t t, uint32_t moved, const double np[3]) const {
  const uint32_t* v = &tri[3 * size_t(t)];
  const double* q[3] = {p(v[0]), p(v[1]), p(v[2])};
  const double* r[3] = {q[0], q[1], q[2]};
  for (int k = 0; k < 3; ++k)
    if (v[k] == moved) r[k] = np;
  double e1[3], e2[3], n_old[3], n_new[3];
  for (int k = 0; k < 3; ++k) { e1[k] = q[1][k] - q[0][k]; e2[k] = q[2][k] - q[0][k]; }
  cross3(e1, e2, n_old);
  double l2max = 0;
  for (int k = 0; k < 3; ++k) { e1[k] = r[1][k] - r[0][k]; e2[k] = r[2][k] - r[0][k]; }
  cross3(e1, e2, n_new);
  for (int i = 0; i < 3; ++i) {
    const double* x = r[i];
    const double* y = r[(i + 1) % 3];
    const double d[3] = {y[0] - x[0], y[1] - x[1], y[2] - x[2]};
    l2max = std::max(l2max, dot3(d, d));
  }
  // Squared lengths compared: no square roots in the common case (min_cos 0).
  const double len2_new = dot3(n_new, n_new);
  // Degenerate: twice the area below 1e-6 of the longest edge squared (a needle or cap
  // thinner than about a micro-radian), or no area at all.
  if (!(len2_new > 1e-12 * l2max * l2max) || !(l2max > 0)) return true;
  const double len2_old = dot3(n_old, n_old);
  if (!(len2_old > 0)) return false;
  const double d = dot3(n_old, n_new);
  if (min_cos == 0) return d <= 0;
  return d <= min_cos * std::sqrt(len2_old * len2_new);
  return false;
}

// Branch-light: which triangles hold both ends is a coin toss per triangle, so the loops
// below write unconditionally and advance their counts by the comparison instead.
Check State::check(uint32_t a, uint32_t b, const double np[3]) {
  for (uint32_t v : {a, b})  // scattered loads: issue them together
    for (uint32_t t : vt(v)) {
      __builtin_prefetch(&tri[3 * size_t(t)]);
      __builtin_prefetch(&tri_alive[t]);
    }
  // Drop dead triangles from both lists first (they are only ever appended to).
  compact(a);
  compact(b);
  const uint32_t na = run_of[a].count, nb = run_of[b].count;
  if (opp.size() < na) {
    opp.resize(na);
    flip_a.resize(na);
  }
  if (flip_b.size() < nb) flip_b.resize(nb);
  // a's triangles: those on the edge give the vertices opposite it (k of them); the two
  // other corners of every triangle of a are marked (mark[] == in_a) for the link
  // condition. Marking b changes nothing below: b is never a corner of b's triangles.
  const uint32_t counted = new_stamps(2), in_a = counted - 1;
  uint32_t* const op = opp.data();
  uint32_t* const fa = flip_a.data();
  uint32_t* const fb = flip_b.data();
  size_t k = 0, nfa = 0, nfb = 0;
  const uint32_t* la = tris_of(a);
  for (uint32_t i = 0; i < na; ++i) {
    const uint32_t t = la[i];
    const uint32_t* v = &tri[3 * size_t(t)];
    const bool has_b = has_corner(v, b);
    uint32_t x, y;
    other_corners(v, a, &x, &y);
    __builtin_prefetch(p(x));  // for the flip tests below: all misses at once
    __builtin_prefetch(p(y));
    mark[x] = in_a;
    mark[y] = in_a;
    op[k] = x ^ y ^ b;  // on the edge, {x, y} = {b, opposite}
    k += has_b;
    fa[nfa] = t;
    nfa += !has_b;
  }
  if (k == 0) return Check::NotEdge;
  if (seam_mode && k != 1) return Check::Refused;  // a seam edge is a border on each side
  if (k > 2) return Check::Refused;                 // non-manifold edge
  if (k > faces - target) return Check::Refused;    // would overshoot the target
  if (k == 2 && (op[0] == op[1] || (border[a] && border[b]))) return Check::Refused;

  // Link condition on vertices: the common neighbours of a and b are exactly the k
  // opposites (each counted once: marks turn from in_a to counted). b's triangles on the
  // edge add a (never marked) and an opposite, which is counted here or in its other
  // triangle.
  // A triangle (b, x, y) would also land on a triangle (a, x, y) after the collapse (e.g.
  // the tetrahedron). Then x and y are common neighbours, so when the link condition holds
  // they are the two opposites: only the pair {opp0, opp1} has to be looked for, in both.
  const uint32_t o0 = op[0], o1 = k == 2 ? op[1] : op[0];
  auto is_opp_pair = [&](uint32_t x, uint32_t y) {
    return k == 2 && (((x == o0) & (y == o1)) | ((x == o1) & (y == o0)));
  };
  bool b_has_pair = false, a_has_pair = false;
  size_t common = 0;
  const uint32_t* lb = tris_of(b);
  for (uint32_t i = 0; i < nb; ++i) {
    const uint32_t t = lb[i];
    const uint32_t* v = &tri[3 * size_t(t)];
    const bool has_a = has_corner(v, a);
    uint32_t x, y;
    other_corners(v, b, &x, &y);
    __builtin_prefetch(p(x));
    __builtin_prefetch(p(y));
    b_has_pair |= is_opp_pair(x, y);
    for (uint32_t z : {x, y}) {
      const bool m = mark[z] == in_a;
      mark[z] = select_u32(m, counted, mark[z]);
      common += m;
    }
    fb[nfb] = t;
    nfb += !has_a;
  }
  if (common != k) return Check::Refused;
  if (b_has_pair) {
    for (uint32_t i = 0; i < na; ++i) {
      uint32_t x, y;
      other_corners(&tri[3 * size_t(la[i])], a, &x, &y);
      a_has_pair |= is_opp_pair(x, y);
    }
    if (a_has_pair) return Check::Refused;
  }

  // Flips, fold-overs and degenerate triangles among those that remain.
  for (size_t i = 0; i < nfa; ++i)
    if (bad_triangle(fa[i], a, np)) return Check::Refused;
  for (size_t i = 0; i < nfb; ++i)
    if (bad_triangle(fb[i], b, np)) return Check::Refused;
  // Twins at one position are one vertex of the surface: the link condition again, welded
  // (along a seam check_edge does it for both sides at once).
  if (has_twins && !seam_mode && (near_seam[a] | near_seam[b]) && !welded_link_ok(a, b, k, false))
    return Check::Refused;
  return Check::Ok;
}

void State::collapse(uint32_t a, uint32_t b, const double np[3], double c) {
  if (nattr && !(has_locks && locked[a])) {
    // Linear along the edge, at the new position's projection onto it.
    double d[3], e[3];
    for (int k = 0; k < 3; ++k) {
      d[k] = vert[b].p[k] - vert[a].p[k];
      e[k] = np[k] - vert[a].p[k];
    }
    const double dd = dot3(d, d);
    const double t = dd > 0 ? std::min(1.0, std::max(0.0, dot3(d, e) / dd)) : 0;
    float* xa = &attr[nattr * a];
    const float* xb = &attr[nattr * b];
    for (size_t i = 0; i < nattr; ++i) xa[i] = float((1 - t) * double(xa[i]) + t * double(xb[i]));
  }
  if (has_twins) {  // a gains b's neighbours; if a is a twin, they gain a twin neighbour
    near_seam[a] |= near_seam[b];
    if (twin_next[a] != NONE)
      for (uint32_t t : vt(b))
        if (tri_alive[t])
          for (int k = 0; k < 3; ++k) near_seam[tri[3 * size_t(t) + k]] = 1;
  }
  for (int k = 0; k < 3; ++k) vert[a].p[k] = np[k];
  vert[a].q += vert[b].q;
  vert[a].plane_weight += vert[b].plane_weight;
  if (!plain.empty()) plain[a] += plain[b];
  if (border[a] && border[b]) --border_vertices;
  border[a] = border[a] | border[b];
  compact(a);
  const uint32_t need = run_of[a].count + run_of[b].count;
  if (need > run_of[a].cap) {  // move a's run to the end of the pool, with room to grow
    const uint32_t cap = need + need / 2;
    if (vt_pool.size() + cap > vt_pool.capacity()) repack();
    const size_t start = vt_pool.size();
    vt_pool.resize(start + cap);
    std::copy(vt_pool.begin() + run_of[a].start, vt_pool.begin() + run_of[a].start + run_of[a].count,
              vt_pool.begin() + start);
    run_of[a].start = uint32_t(start);
    run_of[a].cap = cap;
  }
  uint32_t* la = tris_of(a);
  uint32_t na_ = run_of[a].count;
  const uint32_t* lb = tris_of(b);
  // b's triangles on the edge die; the others take a for b and join a's list. Without
  // branches (which of them is on the edge is a coin toss).
  for (uint32_t i = 0, n = run_of[b].count; i < n; ++i) {
    const uint32_t t = lb[i];
    uint32_t* v = &tri[3 * size_t(t)];
    const bool live = tri_alive[t];
    const bool on_edge = has_corner(v, a);
    const bool moves = live & !on_edge;
    tri_alive[t] = moves;
    faces -= live & on_edge;
    for (int k = 0; k < 3; ++k) v[k] = select_u32(moves & (v[k] == b), a, v[k]);
    la[na_] = t;
    na_ += moves;
  }
  run_of[a].count = na_;
  compact(a);
  run_of[b].count = 0;
  alive[b] = 0;
  ++collapses;
  changed[a] = uint32_t(collapses);
  changed[b] = UINT32_MAX;
  if (record) sequence.push_back({order[a], order[b], c});
}

void State::output_attributes(const Mesh& in, const std::vector<uint32_t>& origin, Mesh* out) const {
  const size_t n = origin.size();
  for (size_t i = 0; i < nattr; ++i) {
    VertexAttribute a{in.attributes[i].name, std::vector<float>(n)};
    for (size_t o = 0; o < n; ++o) a.values[o] = attr[nattr * inv[origin[o]] + i];
    out->attributes.push_back(std::move(a));
  }
  if (normal_at[0] >= 0 && normal_at[1] >= 0 && normal_at[2] >= 0) {
    float* c[3] = {out->attributes[size_t(normal_at[0])].values.data(), out->attributes[size_t(normal_at[1])].values.data(),
                   out->attributes[size_t(normal_at[2])].values.data()};
    for (size_t o = 0; o < n; ++o) {
      if (changed[inv[origin[o]]] == 0) continue;  // never touched: the input's exact normal
      const double len = std::sqrt(double(c[0][o]) * c[0][o] + double(c[1][o]) * c[1][o] + double(c[2][o]) * c[2][o]);
      if (len > 0)
        for (int k = 0; k < 3; ++k) c[k][o] = float(c[k][o] / len);
    }
  }
  // Seam twins are locked, so each group survives whole (or not at all where its
  // triangles went); each points at its group's first survivor.
  if (!in.position_vertex.empty()) {
    std::vector<uint32_t> first(nv, UINT32_MAX);
    out->position_vertex.resize(n);
    bool split = false;
    for (size_t o = 0; o < n; ++o) {
      uint32_t& f = first[in.position_vertex[origin[o]]];
      if (f == UINT32_MAX) f = uint32_t(o);
      out->position_vertex[o] = f;
      split |= f != o;
    }
    if (!split) out->position_vertex.clear();
  }
}

Mesh State::output(SimplifyReport* report) const {
  std::vector<uint32_t> remap(nv, UINT32_MAX);
  Mesh out;
  std::vector<uint32_t> origin;
  for (size_t t = 0; t < tri_alive.size(); ++t)
    if (tri_alive[t])
      for (int k = 0; k < 3; ++k) remap[tri[3 * t + k]] = 0;
  for (size_t iv = 0; iv < nv; ++iv) {  // in input order
    const uint32_t v = inv[iv];
    if (remap[v] == UINT32_MAX) continue;
    remap[v] = uint32_t(origin.size());
    origin.push_back(uint32_t(iv));
    // changed[v] == 0: no collapse ever moved v (a moved vertex has its collapse count).
    for (int k = 0; k < 3; ++k)
      out.positions.push_back(changed[v] == 0 ? input_positions[3 * size_t(iv) + k]
                                              : float(vert[v].p[k] / scale + center[k]));
  }
  out.triangles.reserve(3 * faces);
  for (size_t t = 0; t < tri_alive.size(); ++t)
    if (tri_alive[t])
      for (int k = 0; k < 3; ++k) out.triangles.push_back(remap[tri[3 * t + k]]);
  out.material_libraries = mesh_in->material_libraries;
  out.materials = mesh_in->materials;
  if (!tri_material.empty()) {
    out.triangle_material.reserve(out.triangle_count());
    for (size_t t = 0; t < tri_alive.size(); ++t)
      if (tri_alive[t]) out.triangle_material.push_back(tri_material[t]);
  }
  output_attributes(*mesh_in, origin, &out);
  carry_model_frame(*mesh_in, origin, out);  // an unmoved survivor is written as it was read
  if (report) {
    report->input_faces = tri_alive.size();
    report->target_faces = target;
    report->output_faces = out.triangle_count();
    report->output_vertices = out.vertex_count();
    report->reached = report->output_faces == target;
    report->unchanged = false;
    report->note.clear();
    report->warning = precision_warning(*mesh_in);
    if (!report->reached) {
      bool any_border = false;
      for (size_t v = 0; v < nv && !any_border; ++v) any_border = alive[v] && border[v];
      if (!any_border && faces == target + 1)
        report->note = "target of " + std::to_string(target) +
                       " faces is not reachable: a closed manifold mesh has an even face "
                       "count; stopped at " + std::to_string(faces);
      else if (!report->warning.empty())  // rounding noise folds triangles: not the surface's fault
        report->note = "target of " + std::to_string(target) +
                       " faces is not reachable: the positions are too coarse at float precision (see the "
                       "warning); stopped at " + std::to_string(faces);
      else
        report->note = "target of " + std::to_string(target) +
                       " faces is not reachable: no further collapse keeps the mesh manifold "
                       "and unfolded" + std::string(has_locks ? " and its locked (seam or border) vertices in place" : "") +
                       "; stopped at " + std::to_string(faces);
    }
    report->refused = refused;
    report->error = std::sqrt(reached_error2);
    if (!report->reached && error_refused > 0 && max_error2 < HUGE_VAL)
      report->note = "stopped at " + std::to_string(faces) + " faces (target " + std::to_string(target) +
                     "): every further collapse would exceed the target error or break the mesh";
    report->sequence = sequence;
    report->collapses = tri_alive.size() - faces;  // overwritten by the callers
    report->vertex_origin = std::move(origin);
  }
  return out;
}

}  // namespace

// Invariant of the loop below: every current edge that is not refused has a current entry
// in the heap, with its key; stale entries (an end collapsed or moved since) are skipped.
// So the first current entry popped is the edge that a full scan would pick. A refused
// edge waits in the refused lists of its ends until a collapse changes the 1-ring of one
// of them; then its entry goes back into the heap.
bool simplify_keeps_mesh(const SimplifyOptions& options, size_t face_count) {
  return options.target_faces > 0 ? options.target_faces >= face_count : options.ratio == 1;
}

namespace {

// What simplify_mesh gives when the target asks for the whole mesh.
Mesh unchanged_mesh(const Mesh& mesh, SimplifyReport* report) {
  if (report) {
    *report = SimplifyReport{};
    report->input_faces = report->output_faces = report->target_faces = mesh.triangle_count();
    report->output_vertices = mesh.vertex_count();
    report->reached = report->unchanged = true;
    report->note = "the target is at or above the mesh's " + std::to_string(mesh.triangle_count()) +
                   " faces: the mesh is returned unchanged";
    report->vertex_origin.resize(mesh.vertex_count());
    for (size_t v = 0; v < mesh.vertex_count(); ++v) report->vertex_origin[v] = uint32_t(v);
  }
  return mesh;
}

}  // namespace

Mesh simplify_mesh(const Mesh& mesh, const SimplifyOptions& options,
                   const std::vector<double>* vertex_weights, SimplifyReport* report) {
  if (simplify_keeps_mesh(options, mesh.triangle_count())) return unchanged_mesh(mesh, report);
  const CancelScope cancel(options.cancel);
  const Timer t0;
  State s;
  std::vector<Entry> initial;
  s.init(mesh, options, vertex_weights, &initial);
  EdgeQueue heap;
  for (const Entry& x : initial)
    if (!s.both_locked(x.a, x.b)) heap.push(x);
  std::vector<Entry>().swap(initial);

  std::vector<std::vector<Entry>> refused(s.nv);
  // Puts the refused edges of w back (both ends' lists forget them).
  // Whether refused[w] is not empty: one byte per vertex stays in cache, the vectors not.
  std::vector<uint8_t> has_refused(s.nv, 0);
  auto release_one = [&](uint32_t w) {
    if (!has_refused[w]) return;
    has_refused[w] = 0;
    for (const Entry& e : refused[w]) {
      const uint32_t z = e.a ^ e.b ^ w;
      auto& l = refused[z];
      for (size_t i = 0; i < l.size(); ++i)
        if (l[i].a == e.a && l[i].b == e.b) { l[i] = l.back(); l.pop_back(); break; }
      has_refused[z] = !l.empty();
      if (s.current(e)) heap.push(e);
    }
    refused[w].clear();
  };
  // A seam twin's edges also depend on its twins' neighbourhoods (welded_link_ok).
  auto release = [&](uint32_t w) {
    release_one(w);
    if (s.has_twins && s.twin_next[w] != State::NONE)
      for (uint32_t x = s.twin_next[w]; x != w; x = s.twin_next[x]) release_one(x);
  };

  std::vector<uint32_t> ring;
  double np[3];
  // Stale entries waiting in the queue only cost memory (they are dropped when their
  // bucket comes up): sweep them out in one pass whenever the queue has doubled since the
  // last sweep, so that sweeping costs O(1) per push and memory stays within 2x.
  size_t sweep_at = 2 * heap.size() + 4096;
  const auto current = [&](const Entry& x) { return s.current(x); };
  // After a collapse into a: its new 1-ring's refused edges count again, and every edge
  // of a gets a fresh entry.
  const auto refresh = [&](uint32_t a) {
    const uint32_t now = uint32_t(s.collapses), stamp = s.new_stamps(1);
    std::vector<uint32_t>& mark = s.mark;
    // The new 1-ring of a; its quadrics are scattered in memory: prefetch them together.
    mark[a] = stamp;
    const uint32_t* tl = s.tris_of(a);
    if (ring.size() < 2 * size_t(s.run_of[a].count) + 1) ring.resize(2 * size_t(s.run_of[a].count) + 1);
    size_t nring = 0;
    for (uint32_t i = 0, n = s.run_of[a].count; i < n; ++i) {
      const uint32_t* tv = &s.tri[3 * size_t(tl[i])];
      for (int k = 0; k < 3; ++k) {  // no branch on the mark: seen or not is random
        const uint32_t y = tv[k];
        ring[nring] = y;
        nring += mark[y] != stamp;
        mark[y] = stamp;
        __builtin_prefetch(&s.vert[y]);
        __builtin_prefetch(reinterpret_cast<const char*>(&s.vert[y]) + 64);
      }
    }
    release(a);
    for (size_t i = 0; i < nring; ++i) release(ring[i]);
    double tmp[3];
    for (size_t i = 0; i < nring; ++i) {
      const uint32_t y = ring[i];
      const uint32_t lo = select_u32(a < y, a, y), hi = select_u32(a < y, y, a);
      if (s.both_locked(lo, hi)) continue;
      heap.push(make_entry(s.cost(lo, hi, tmp), lo, hi, now));
    }
  };
  size_t polls = 0;
  while (s.faces > s.target) {
    if ((++polls & 4095) == 0) throw_if_cancelled();
    // One face short on a closed manifold surface: every collapse removes two faces and
    // would overshoot, so the scan below would refuse every edge left. Stop now instead
    // (same result; the report's note says why).
    if (s.faces == s.target + 1 && s.border_vertices == 0) break;
    if (heap.size() > sweep_at) {
      heap.filter(current);
      sweep_at = 2 * heap.size() + 4096;
    }
    if (!heap.ready(current)) break;
    const Entry e = heap.pop();
    if (heap.has_top()) {  // the next pick's data, while this one is worked on
      const Entry& n = heap.top();
      __builtin_prefetch(&s.changed[n.a]);
      __builtin_prefetch(&s.changed[n.b]);
      __builtin_prefetch(&s.run_of[n.a]);
      __builtin_prefetch(&s.run_of[n.b]);
      __builtin_prefetch(&s.vert[n.a]);
      __builtin_prefetch(&s.vert[n.b]);
      __builtin_prefetch(reinterpret_cast<const char*>(&s.vert[n.a]) + 64);
      __builtin_prefetch(reinterpret_cast<const char*>(&s.vert[n.b]) + 64);
    }
    if (!s.current(e)) continue;
    const double exact = s.cost(e.a, e.b, np);
    const Check c = s.over_error(e.a, e.b, np, exact) ? Check::Refused : s.check_edge(e.a, e.b, np);
    if (c != Check::Ok) {
      ++s.refused;
      refused[e.a].push_back(e);
      refused[e.b].push_back(e);
      has_refused[e.a] = has_refused[e.b] = 1;
      continue;
    }
    uint32_t kept[2], removed[2];
    const int made = s.apply(e.a, e.b, np, exact, kept, removed);
    for (int i = 0; i < made; ++i)
      if (has_refused[removed[i]]) {
        std::vector<Entry>().swap(refused[removed[i]]);
        has_refused[removed[i]] = 0;
      }
    for (int i = 0; i < made; ++i) refresh(kept[i]);
    if (heap.has_top()) {  // the next pick's triangles, for its check
      const Entry& n = heap.top();
      for (uint32_t v : {n.a, n.b})
        for (uint32_t t : s.vt(v)) __builtin_prefetch(&s.tri[3 * size_t(t)]);
    }
    // A seam edge's cost holds the partners' quadrics: a partner whose twin took a
    // collapse has changed too.
    if (made == 1 && s.pair(kept[0])) {
      const uint32_t w = s.partner[kept[0]];
      s.changed[w] = uint32_t(s.collapses);
      s.compact(w);
      refresh(w);
    }
  }
  Mesh out = s.output(report);
  if (report) {
    report->collapses = s.collapses;
    report->seconds = t0.seconds();
  }
  return out;
}

Mesh simplify_bruteforce(const Mesh& mesh, const SimplifyOptions& options,
                         const std::vector<double>* vertex_weights, SimplifyReport* report) {
  const Timer t0;
  State s;
  s.init(mesh, options, vertex_weights, nullptr);
  std::vector<Entry> cand;
  while (s.faces > s.target) {
    cand.clear();
    for (size_t t = 0; t < s.tri_alive.size(); ++t) {
      if (!s.tri_alive[t]) continue;
      for (int k = 0; k < 3; ++k) {
        const uint32_t x = s.tri[3 * t + k], y = s.tri[3 * t + (k + 1) % 3];
        cand.push_back(make_entry(0, std::min(x, y), std::max(x, y), 0));
      }
    }
    std::sort(cand.begin(), cand.end(), [](const Entry& x, const Entry& y) {
      return x.a != y.a ? x.a < y.a : x.b < y.b;
    });
    cand.erase(std::unique(cand.begin(), cand.end(),
                           [](const Entry& x, const Entry& y) { return x.a == y.a && x.b == y.b; }),
               cand.end());
    cand.erase(std::remove_if(cand.begin(), cand.end(), [&](const Entry& e) { return s.both_locked(e.a, e.b); }),
               cand.end());
    double tmp[3];
    for (Entry& e : cand) e.cost = float(s.cost(e.a, e.b, tmp));
    std::sort(cand.begin(), cand.end(), key_less);
    bool done = false;
    for (const Entry& e : cand) {
      double np[3];
      const double exact = s.cost(e.a, e.b, np);
      if (s.over_error(e.a, e.b, np, exact) || s.check_edge(e.a, e.b, np) != Check::Ok) {
        ++s.refused;
        continue;
      }
      uint32_t kept[2], removed[2];
      s.apply(e.a, e.b, np, exact, kept, removed);
      done = true;
      break;
    }
    if (!done) break;
  }
  Mesh out = s.output(report);
  if (report) {
    report->collapses = s.collapses;
    report->seconds = t0.seconds();
  }
  return out;
}

}  // namespace meshsal
