// meshsal: Garland-Heckbert edge-collapse simplification over flat arrays.
// One shared state (positions, quadrics, vertex -> triangle lists) with two ways to pick
// the next collapse: an indexed heap of per-vertex cheapest edges (simplify_mesh) and a full scan
// (simplify_bruteforce, the test oracle). Both use the same cost, check and collapse code.
#include "meshsal/simplify.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cmath>
#include <string>

#include "meshsal/error.h"
#include "meshsal/quadric.h"

namespace meshsal {

size_t resolve_target_faces(const SimplifyOptions& options, size_t input_faces) {
  if (input_faces == 0) throw Error("simplify: the mesh has no non-degenerate triangles");
  size_t target = options.target_faces;
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

namespace {

// 16 bytes, so that the heap stays cache friendly. The order key is the cost rounded to
// float (ties then break on the vertex indices); the exact cost is recomputed on collapse.
struct Entry {
  float cost;
  uint32_t a, b;   // a < b; a survives
  uint32_t stamp;  // collapse count when the cost was computed
};

// Orders by (cost, a, b): the deterministic tie-break shared by both simplifiers.
inline bool key_less(const Entry& x, const Entry& y) {
  if (x.cost != y.cost) return x.cost < y.cost;
  if (x.a != y.a) return x.a < y.a;
  return x.b < y.b;
}
struct HeapGreater {
  bool operator()(const Entry& x, const Entry& y) const { return key_less(y, x); }
};

enum class Check { Ok, NotEdge, Refused };

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
  std::vector<double> pos;                   // 3 per vertex, internal coordinates
  std::vector<Quadric> quad;
  std::vector<uint32_t> tri;                 // 3 per triangle
  std::vector<uint8_t> tri_alive;
  std::vector<std::vector<uint32_t>> vtris;  // triangles of each vertex (may hold dead ones)
  std::vector<uint8_t> alive;
  std::vector<uint8_t> border;               // on an open border or a non-manifold edge
  std::vector<uint32_t> changed;             // collapse count when the vertex last moved
  std::vector<uint32_t> order;               // internal vertex id -> input vertex
  std::vector<uint32_t> inv;                 // input vertex -> internal id
  size_t faces = 0;
  size_t target = 0;
  double min_cos = 0;
  size_t refused = 0;
  std::vector<Collapse> sequence;
  bool record = false;
  // scratch
  std::vector<uint32_t> na, nb, opp;
  std::vector<uint64_t> pairs_a;

  const double* p(uint32_t v) const { return &pos[3 * size_t(v)]; }

  double cost(uint32_t a, uint32_t b, double out[3]) const {
    return optimal_placement(quad[a] + quad[b], p(a), p(b), out);
  }

  void init(const Mesh& mesh, const SimplifyOptions& options, const std::vector<double>* w,
            std::vector<Entry>* edges);
  Check check(uint32_t a, uint32_t b, const double np[3]);
  // Would triangle t, with vertex `moved` placed at np, flip, fold or degenerate?
  bool bad_triangle(uint32_t t, uint32_t moved, const double np[3]) const;
  void collapse(uint32_t a, uint32_t b, const double np[3], double cost);
  // An entry is current while neither end has changed since its cost was computed.
  bool current(const Entry& e) const {
    return alive[e.a] && alive[e.b] && changed[e.a] <= e.stamp && changed[e.b] <= e.stamp;
  }
  size_t collapses = 0;
  Mesh output(SimplifyReport* report) const;
};

void State::init(const Mesh& mesh, const SimplifyOptions& options, const std::vector<double>* w,
                 std::vector<Entry>* edges) {
  nv = mesh.vertex_count();
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
  tri.reserve(3 * nt_in);
  for (size_t t = 0; t < nt_in; ++t) {
    const uint32_t* v = &mesh.triangles[3 * t];
    if (v[0] == v[1] || v[1] == v[2] || v[0] == v[2]) continue;
    tri.insert(tri.end(), v, v + 3);
  }
  const size_t nt = tri.size() / 3;
  faces = nt;
  target = resolve_target_faces(options, nt);
  min_cos = options.min_normal_cos;
  record = options.record_collapses;

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
    std::vector<uint64_t> code(nv);
    const double inv_ext[3] = {hi[0] > lo[0] ? 1 / (hi[0] - lo[0]) : 0, hi[1] > lo[1] ? 1 / (hi[1] - lo[1]) : 0,
                               hi[2] > lo[2] ? 1 / (hi[2] - lo[2]) : 0};
    for (size_t v = 0; v < nv; ++v) {
      uint64_t c = 0;
      if (alive[v]) {
        uint32_t q[3];
        for (int k = 0; k < 3; ++k)
          q[k] = uint32_t(std::min(1.0, std::max(0.0, (mesh.positions[3 * v + k] - lo[k]) * inv_ext[k])) * 1023.0);
        for (int bit = 9; bit >= 0; --bit)
          for (int k = 0; k < 3; ++k) c = (c << 1) | ((q[k] >> bit) & 1u);
      } else {
        c = UINT64_MAX;
      }
      code[v] = c;
      order[v] = uint32_t(v);
    }
    std::stable_sort(order.begin(), order.end(), [&](uint32_t x, uint32_t y) { return code[x] < code[y]; });
  }
  inv.resize(nv);
  for (size_t i = 0; i < nv; ++i) inv[order[i]] = uint32_t(i);
  for (uint32_t& v : tri) v = inv[v];
  {
    std::vector<uint8_t> a2(nv);
    for (size_t i = 0; i < nv; ++i) a2[i] = alive[order[i]];
    alive.swap(a2);
  }
  pos.resize(3 * nv);
  for (size_t i = 0; i < nv; ++i)
    for (int k = 0; k < 3; ++k)
      pos[3 * i + k] = (mesh.positions[3 * size_t(order[i]) + k] - center[k]) * scale;

  tri_alive.assign(nt, 1);
  std::vector<uint32_t> deg(nv, 0);
  for (uint32_t v : tri) ++deg[v];
  vtris.resize(nv);
  for (size_t v = 0; v < nv; ++v) vtris[v].reserve(deg[v]);
  quad.assign(nv, Quadric{});
  for (size_t t = 0; t < nt; ++t) {
    const uint32_t* v = &tri[3 * t];
    const Quadric q = triangle_quadric(p(v[0]), p(v[1]), p(v[2]));
    for (int k = 0; k < 3; ++k) {
      vtris[v[k]].push_back(uint32_t(t));
      quad[v[k]] += q;
    }
  }

  // Edges: sort (min, max, triangle) keys; a run of one is a border edge, more than two a
  // non-manifold edge.
  struct EdgeRef { uint64_t key; uint32_t t; uint32_t corner; };
  std::vector<EdgeRef> refs(3 * nt);
  for (size_t t = 0; t < nt; ++t)
    for (int k = 0; k < 3; ++k) {
      const uint32_t a = tri[3 * t + k], b = tri[3 * t + (k + 1) % 3];
      refs[3 * t + k] = {(uint64_t(std::min(a, b)) << 32) | std::max(a, b), uint32_t(t), uint32_t(k)};
    }
  std::sort(refs.begin(), refs.end(), [](const EdgeRef& x, const EdgeRef& y) {
    return x.key != y.key ? x.key < y.key : x.t < y.t;
  });
  border.assign(nv, 0);
  std::vector<uint32_t> unique_edges_a, unique_edges_b;
  for (size_t i = 0; i < refs.size();) {
    size_t j = i;
    while (j < refs.size() && refs[j].key == refs[i].key) ++j;
    const uint32_t a = uint32_t(refs[i].key >> 32), b = uint32_t(refs[i].key & 0xffffffffu);
    if (j - i == 1) {
      const uint32_t t = refs[i].t, k = refs[i].corner;
      const uint32_t v0 = tri[3 * t + k], v1 = tri[3 * t + (k + 1) % 3], v2 = tri[3 * t + (k + 2) % 3];
      const Quadric q = border_quadric(p(v0), p(v1), p(v2), options.border_weight);
      quad[v0] += q;
      quad[v1] += q;
      border[a] = border[b] = 1;
    } else if (j - i > 2) {
      border[a] = border[b] = 1;
    }
    unique_edges_a.push_back(a);
    unique_edges_b.push_back(b);
    i = j;
  }
  if (w)
    for (size_t v = 0; v < nv; ++v) quad[v] *= (*w)[order[v]];
  changed.assign(nv, 0);

  if (edges) {
    edges->resize(unique_edges_a.size());
    double tmp[3];
    for (size_t i = 0; i < unique_edges_a.size(); ++i) {
      const uint32_t a = unique_edges_a[i], b = unique_edges_b[i];
      (*edges)[i] = {float(cost(a, b, tmp)), a, b, 0};
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
  const double len_new = std::sqrt(dot3(n_new, n_new));
  // Degenerate: twice the area below 1e-6 of the longest edge squared (a needle or cap
  // thinner than about a micro-radian), or no area at all.
  if (!(len_new > 1e-6 * l2max)) return true;
  const double len_old = std::sqrt(dot3(n_old, n_old));
  if (len_old > 0 && dot3(n_old, n_new) <= min_cos * len_old * len_new) return true;
  return false;
}

Check State::check(uint32_t a, uint32_t b, const double np[3]) {
  for (uint32_t v : {a, b})  // scattered loads: issue them together
    for (uint32_t t : vtris[v]) {
      __builtin_prefetch(&tri[3 * size_t(t)]);
      __builtin_prefetch(&tri_alive[t]);
    }
  // Drop dead triangles from both lists first (they are only ever appended to).
  for (uint32_t v : {a, b}) {
    std::vector<uint32_t>& l = vtris[v];
    l.erase(std::remove_if(l.begin(), l.end(), [&](uint32_t t) { return !tri_alive[t]; }), l.end());
  }
  // Triangles on the edge and the vertices opposite it.
  opp.clear();
  for (uint32_t t : vtris[a]) {
    if (!tri_alive[t]) continue;
    const uint32_t* v = &tri[3 * size_t(t)];
    if (v[0] == b || v[1] == b || v[2] == b) opp.push_back(v[0] ^ v[1] ^ v[2] ^ a ^ b);
  }
  const size_t k = opp.size();
  if (k == 0) return Check::NotEdge;
  if (k > 2) return Check::Refused;                 // non-manifold edge
  if (k > faces - target) return Check::Refused;    // would overshoot the target
  if (k == 2 && (opp[0] == opp[1] || (border[a] && border[b]))) return Check::Refused;

  // Link condition on vertices: the common neighbours of a and b are exactly the opposites.
  na.clear();
  nb.clear();
  pairs_a.clear();
  for (uint32_t t : vtris[a]) {
    if (!tri_alive[t]) continue;
    const uint32_t* v = &tri[3 * size_t(t)];
    if (v[0] == b || v[1] == b || v[2] == b) continue;
    uint32_t x = 0, y = 0;
    int n = 0;
    for (int i = 0; i < 3; ++i)
      if (v[i] != a) { na.push_back(v[i]); (n++ == 0 ? x : y) = v[i]; }
    pairs_a.push_back((uint64_t(std::min(x, y)) << 32) | std::max(x, y));
  }
  for (uint32_t t : vtris[b]) {
    if (!tri_alive[t]) continue;
    const uint32_t* v = &tri[3 * size_t(t)];
    if (v[0] == a || v[1] == a || v[2] == a) continue;
    uint32_t x = 0, y = 0;
    int n = 0;
    for (int i = 0; i < 3; ++i)
      if (v[i] != b) { nb.push_back(v[i]); (n++ == 0 ? x : y) = v[i]; }
    // A triangle of b that would coincide with one of a after the collapse (e.g. the
    // tetrahedron): refuse.
    const uint64_t key = (uint64_t(std::min(x, y)) << 32) | std::max(x, y);
    for (uint64_t pa : pairs_a)
      if (pa == key) return Check::Refused;
  }
  for (uint32_t o : opp) { na.push_back(o); nb.push_back(o); }
  std::sort(na.begin(), na.end());
  na.erase(std::unique(na.begin(), na.end()), na.end());
  std::sort(nb.begin(), nb.end());
  nb.erase(std::unique(nb.begin(), nb.end()), nb.end());
  size_t common = 0;
  for (size_t i = 0, j = 0; i < na.size() && j < nb.size();) {
    if (na[i] < nb[j]) ++i;
    else if (nb[j] < na[i]) ++j;
    else { ++common; ++i; ++j; }
  }
  if (common != k) return Check::Refused;

  // Flips, fold-overs and degenerate triangles among those that remain.
  for (uint32_t t : vtris[a]) {
    if (!tri_alive[t]) continue;
    const uint32_t* v = &tri[3 * size_t(t)];
    if (v[0] == b || v[1] == b || v[2] == b) continue;
    if (bad_triangle(t, a, np)) return Check::Refused;
  }
  for (uint32_t t : vtris[b]) {
    if (!tri_alive[t]) continue;
    const uint32_t* v = &tri[3 * size_t(t)];
    if (v[0] == a || v[1] == a || v[2] == a) continue;
    if (bad_triangle(t, b, np)) return Check::Refused;
  }
  return Check::Ok;
}

void State::collapse(uint32_t a, uint32_t b, const double np[3], double c) {
  for (int k = 0; k < 3; ++k) pos[3 * size_t(a) + k] = np[k];
  quad[a] += quad[b];
  border[a] = border[a] | border[b];
  for (uint32_t t : vtris[b]) {
    if (!tri_alive[t]) continue;
    uint32_t* v = &tri[3 * size_t(t)];
    if (v[0] == a || v[1] == a || v[2] == a) {
      tri_alive[t] = 0;
      --faces;
    } else {
      for (int k = 0; k < 3; ++k)
        if (v[k] == b) v[k] = a;
      vtris[a].push_back(t);
    }
  }
  std::vector<uint32_t>& la = vtris[a];
  la.erase(std::remove_if(la.begin(), la.end(), [&](uint32_t t) { return !tri_alive[t]; }),
           la.end());
  std::vector<uint32_t>().swap(vtris[b]);
  alive[b] = 0;
  ++collapses;
  changed[a] = changed[b] = uint32_t(collapses);
  if (record) sequence.push_back({order[a], order[b], c});
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
    for (int k = 0; k < 3; ++k)
      out.positions.push_back(float(pos[3 * v + k] / scale + center[k]));
  }
  out.triangles.reserve(3 * faces);
  for (size_t t = 0; t < tri_alive.size(); ++t)
    if (tri_alive[t])
      for (int k = 0; k < 3; ++k) out.triangles.push_back(remap[tri[3 * t + k]]);
  if (report) {
    report->input_faces = tri_alive.size();
    report->target_faces = target;
    report->output_faces = out.triangle_count();
    report->output_vertices = out.vertex_count();
    report->reached = report->output_faces == target;
    report->note.clear();
    if (!report->reached) {
      bool any_border = false;
      for (size_t v = 0; v < nv && !any_border; ++v) any_border = alive[v] && border[v];
      if (!any_border && faces == target + 1)
        report->note = "target of " + std::to_string(target) +
                       " faces is not reachable: a closed manifold mesh has an even face "
                       "count; stopped at " + std::to_string(faces);
      else
        report->note = "target of " + std::to_string(target) +
                       " faces is not reachable: no further collapse keeps the mesh manifold "
                       "and unfolded; stopped at " + std::to_string(faces);
    }
    report->refused = refused;
    report->sequence = sequence;
    report->collapses = tri_alive.size() - faces;  // overwritten by the callers
    report->vertex_origin = std::move(origin);
  }
  return out;
}

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

// Indexed 4-ary min-heap over vertices, keyed by each vertex's cheapest edge. Only the
// vertices whose cheapest edge changed are touched per collapse, and nothing goes stale.
class VertexHeap {
 public:
  explicit VertexHeap(const std::vector<Entry>& best) : best_(best), pos_(best.size(), kNone) {}
  bool empty() const { return h_.empty(); }
  uint32_t top() const { return h_[0]; }
  // Inserts v or moves it to its place after best_[v] changed.
  void update(uint32_t v) {
    if (pos_[v] == kNone) {
      pos_[v] = uint32_t(h_.size());
      h_.push_back(v);
      up(pos_[v]);
    } else {
      up(pos_[v]);
      down(pos_[v]);
    }
  }
  void remove(uint32_t v) {
    const uint32_t i = pos_[v];
    if (i == kNone) return;
    pos_[v] = kNone;
    const uint32_t last = h_.back();
    h_.pop_back();
    if (i < h_.size()) {
      h_[i] = last;
      pos_[last] = i;
      up(i);
      down(pos_[last]);
    }
  }

 private:
  static constexpr uint32_t kNone = UINT32_MAX;
  bool less(uint32_t x, uint32_t y) const {
    const Entry& ex = best_[x];
    const Entry& ey = best_[y];
    if (key_less(ex, ey)) return true;
    if (key_less(ey, ex)) return false;
    return x < y;  // the two ends of one edge: any fixed order
  }
  void up(uint32_t i) {
    const uint32_t v = h_[i];
    while (i > 0) {
      const uint32_t parent = (i - 1) / 4;
      if (!less(v, h_[parent])) break;
      h_[i] = h_[parent];
      pos_[h_[i]] = i;
      i = parent;
    }
    h_[i] = v;
    pos_[v] = i;
  }
  void down(uint32_t i) {
    const size_t n = h_.size();
    const uint32_t v = h_[i];
    for (;;) {
      const size_t c = 4 * size_t(i) + 1;
      if (c >= n) break;
      size_t m = c;
      const size_t end = std::min(c + 4, n);
      for (size_t j = c + 1; j < end; ++j)
        if (less(h_[j], h_[m])) m = j;
      if (!less(h_[m], v)) break;
      h_[i] = h_[m];
      pos_[h_[i]] = i;
      i = uint32_t(m);
    }
    h_[i] = v;
    pos_[v] = i;
  }
  const std::vector<Entry>& best_;
  std::vector<uint32_t> pos_;
  std::vector<uint32_t> h_;
};

// Invariant of the loop below: best[v] is the current key of a current, not refused edge of
// v (or infinite), and every current, not refused edge has an end whose best[] orders at or
// before it. So the heap's top is the edge that a full scan would pick.
Mesh simplify_mesh(const Mesh& mesh, const SimplifyOptions& options,
                   const std::vector<double>* vertex_weights, SimplifyReport* report) {
  const auto t0 = std::chrono::steady_clock::now();
  State s;
  std::vector<Entry> initial;
  s.init(mesh, options, vertex_weights, &initial);
  const Entry none{HUGE_VALF, UINT32_MAX, UINT32_MAX, 0};
  std::vector<Entry> best(s.nv, none);
  for (const Entry& e : initial) {
    if (key_less(e, best[e.a])) best[e.a] = e;
    if (key_less(e, best[e.b])) best[e.b] = e;
  }
  VertexHeap heap(best);
  for (uint32_t v = 0; v < s.nv; ++v)
    if (s.alive[v] && best[v].a != UINT32_MAX) heap.update(v);

  // Every current edge with its key, listed at both ends: a collapse only re-costs the edges
  // of the surviving vertex.
  std::vector<std::vector<Entry>> edges(s.nv);
  {
    std::vector<uint32_t> count(s.nv, 0);
    for (const Entry& e : initial) { ++count[e.a]; ++count[e.b]; }
    for (uint32_t v = 0; v < s.nv; ++v) edges[v].reserve(count[v]);
    for (const Entry& e : initial) { edges[e.a].push_back(e); edges[e.b].push_back(e); }
  }
  std::vector<Entry>().swap(initial);
  // Refused edges, listed at both ends; they count again once a collapse changes the 1-ring
  // of either end.
  std::vector<std::vector<uint32_t>> refused(s.nv);
  auto is_refused = [&](uint32_t v, uint32_t y) {
    for (uint32_t z : refused[v])
      if (z == y) return true;
    return false;
  };
  // best[v] from the listed edges of v that are not refused.
  auto rescan = [&](uint32_t v) {
    Entry b = none;
    for (const Entry& e : edges[v])
      if (key_less(e, b) && (refused[v].empty() || !is_refused(v, e.a ^ e.b ^ v))) b = e;
    best[v] = b;
    heap.update(v);
  };
  auto partner = [](const Entry& e, uint32_t v) { return e.a ^ e.b ^ v; };

  std::vector<uint32_t> mark(s.nv, UINT32_MAX);
  std::vector<uint32_t> redo;
  double np[3];
  while (s.faces > s.target && !heap.empty()) {
    const uint32_t v = heap.top();
    const Entry e = best[v];
    if (e.a == UINT32_MAX) break;  // no edge left anywhere
    const double exact = s.cost(e.a, e.b, np);
    const Check c = s.check(e.a, e.b, np);
    if (c != Check::Ok) {
      ++s.refused;
      refused[e.a].push_back(e.b);
      refused[e.b].push_back(e.a);
      const uint32_t other = partner(e, v);
      rescan(v);
      if (best[other].a == e.a && best[other].b == e.b) rescan(other);
      continue;
    }
    const uint32_t a = e.a, b = e.b;
    s.collapse(a, b, np, exact);
    heap.remove(b);
    std::vector<uint32_t>().swap(refused[b]);
    std::vector<Entry>().swap(edges[b]);
    // The new edges of a, with their costs.
    const uint32_t now = uint32_t(s.collapses);
    // Loads below go to scattered memory (the ring's quadrics and edge lists): they are
    // prefetched all at once instead of one miss after the other.
    std::vector<Entry>& ea = edges[a];
    ea.clear();
    mark[a] = now;
    double tmp[3];
    for (uint32_t t : s.vtris[a]) {
      const uint32_t* tv = &s.tri[3 * size_t(t)];
      for (int k = 0; k < 3; ++k) {
        const uint32_t y = tv[k];
        if (mark[y] == now) continue;
        mark[y] = now;
        ea.push_back({0, std::min(a, y), std::max(a, y), 0});
        __builtin_prefetch(&s.quad[y]);
        __builtin_prefetch(reinterpret_cast<const char*>(&s.quad[y]) + 64);
        __builtin_prefetch(edges[y].data());
      }
    }
    for (Entry& ey : ea) ey.cost = float(s.cost(ey.a, ey.b, tmp));
    // The 1-ring of a changed: refused edges there count again (at both ends).
    auto release = [&](uint32_t w) {
      for (uint32_t z : refused[w]) {
        auto& l = refused[z];
        auto it = std::find(l.begin(), l.end(), w);
        if (it != l.end()) { *it = l.back(); l.pop_back(); }
      }
      const bool had = !refused[w].empty();
      refused[w].clear();
      return had;
    };
    release(a);
    redo.clear();
    for (const Entry& ey : ea)
      if (release(partner(ey, a))) redo.push_back(partner(ey, a));
    rescan(a);
    for (const Entry& ey : ea) {
      const uint32_t y = partner(ey, a);
      std::vector<Entry>& l = edges[y];
      for (size_t i = 0; i < l.size();) {
        const uint32_t z = partner(l[i], y);
        if (z == a || z == b) { l[i] = l.back(); l.pop_back(); }
        else ++i;
      }
      l.push_back(ey);
      const Entry& by = best[y];
      const uint32_t py = by.a == UINT32_MAX ? UINT32_MAX : partner(by, y);
      if (py == a || py == b || py == UINT32_MAX ||
          std::find(redo.begin(), redo.end(), y) != redo.end()) {
        rescan(y);
      } else if (key_less(ey, by)) {
        best[y] = ey;
        heap.update(y);
      }
    }
  }
  Mesh out = s.output(report);
  if (report) {
    report->collapses = s.collapses;
    report->seconds = seconds_since(t0);
  }
  return out;
}

Mesh simplify_bruteforce(const Mesh& mesh, const SimplifyOptions& options,
                         const std::vector<double>* vertex_weights, SimplifyReport* report) {
  const auto t0 = std::chrono::steady_clock::now();
  State s;
  s.init(mesh, options, vertex_weights, nullptr);
  std::vector<Entry> cand;
  while (s.faces > s.target) {
    cand.clear();
    for (size_t t = 0; t < s.tri_alive.size(); ++t) {
      if (!s.tri_alive[t]) continue;
      for (int k = 0; k < 3; ++k) {
        const uint32_t x = s.tri[3 * t + k], y = s.tri[3 * t + (k + 1) % 3];
        cand.push_back({0, std::min(x, y), std::max(x, y), 0});
      }
    }
    std::sort(cand.begin(), cand.end(), [](const Entry& x, const Entry& y) {
      return x.a != y.a ? x.a < y.a : x.b < y.b;
    });
    cand.erase(std::unique(cand.begin(), cand.end(),
                           [](const Entry& x, const Entry& y) { return x.a == y.a && x.b == y.b; }),
               cand.end());
    double tmp[3];
    for (Entry& e : cand) e.cost = float(s.cost(e.a, e.b, tmp));
    std::sort(cand.begin(), cand.end(), key_less);
    bool done = false;
    for (const Entry& e : cand) {
      double np[3];
      const double exact = s.cost(e.a, e.b, np);
      if (s.check(e.a, e.b, np) != Check::Ok) {
        ++s.refused;
        continue;
      }
      s.collapse(e.a, e.b, np, exact);
      done = true;
      break;
    }
    if (!done) break;
  }
  Mesh out = s.output(report);
  if (report) {
    report->collapses = s.collapses;
    report->seconds = seconds_since(t0);
  }
  return out;
}

}  // namespace meshsal
