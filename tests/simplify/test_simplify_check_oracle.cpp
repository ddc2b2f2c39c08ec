// The collapse check (src/simplify/collapse_check.*) against a brute-force oracle that
// shares no code with the simplifier: neighbourhoods are rebuilt from the raw list of live
// triangles with std::set, the link condition is checked as set equality
// lk(a) ∩ lk(b) == lk(ab) (the border closed by a cone vertex, after Dey et al.), and flips
// by recomputing the normal of every face after the hypothetical collapse. Many random
// collapses (and random new positions) on small synthetic meshes, closed, with borders,
// with holes and with seams, while the meshes are simplified step by step.
#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <random>
#include <set>
#include <sstream>
#include <utility>
#include <vector>

#include "cli/synthetic.h"
#include "meshsal/meshsal.h"
#include "simplify/simplify_state.h"

using namespace meshsal;

namespace {

// ---------------------------------------------------------------------------------------
// The oracle. Reads only triangles (corner ids), positions and position groups.
namespace oracle {

using Tri = std::array<uint32_t, 3>;
using P3 = std::array<double, 3>;
using Edge = std::pair<uint32_t, uint32_t>;
constexpr uint32_t kOmega = UINT32_MAX;  // the cone vertex over the border

enum class Verdict { NotEdge, Refused, Ok };

Edge edge(uint32_t x, uint32_t y) { return {std::min(x, y), std::max(x, y)}; }

bool has(const Tri& t, uint32_t v) { return t[0] == v || t[1] == v || t[2] == v; }

// How many triangles hold each undirected edge.
std::map<Edge, int> edge_use(const std::vector<Tri>& tris) {
  std::map<Edge, int> use;
  for (const Tri& t : tris)
    for (int k = 0; k < 3; ++k) ++use[edge(t[k], t[(k + 1) % 3])];
  return use;
}

struct Link {
  std::set<uint32_t> vertices;
  std::set<Edge> edges;
  bool operator==(const Link& o) const { return vertices == o.vertices && edges == o.edges; }
};

// The link of v in the surface closed by a cone over its border: each border edge (v, x)
// also bounds the triangle (v, x, omega).
Link link_of_vertex(uint32_t v, const std::vector<Tri>& tris, const std::map<Edge, int>& use) {
  Link l;
  for (const Tri& t : tris)
    for (int k = 0; k < 3; ++k) {
      if (t[k] != v) continue;
      const uint32_t x = t[(k + 1) % 3], y = t[(k + 2) % 3];
      l.vertices.insert(x);
      l.vertices.insert(y);
      l.edges.insert(edge(x, y));
      for (uint32_t z : {x, y})
        if (use.at(edge(v, z)) == 1) {
          l.vertices.insert(kOmega);
          l.edges.insert(edge(z, kOmega));
        }
    }
  return l;
}

Link link_of_edge(uint32_t a, uint32_t b, const std::vector<Tri>& tris, const std::map<Edge, int>& use) {
  Link l;
  for (const Tri& t : tris)
    if (has(t, a) && has(t, b))
      for (uint32_t c : t)
        if (c != a && c != b) l.vertices.insert(c);
  if (use.at(edge(a, b)) == 1) l.vertices.insert(kOmega);
  return l;
}

bool link_condition(uint32_t a, uint32_t b, const std::vector<Tri>& tris) {
  const std::map<Edge, int> use = edge_use(tris);
  const Link la = link_of_vertex(a, tris, use), lb = link_of_vertex(b, tris, use);
  Link both;
  std::set_intersection(la.vertices.begin(), la.vertices.end(), lb.vertices.begin(), lb.vertices.end(),
                        std::inserter(both.vertices, both.vertices.end()));
  std::set_intersection(la.edges.begin(), la.edges.end(), lb.edges.begin(), lb.edges.end(),
                        std::inserter(both.edges, both.edges.end()));
  return both == link_of_edge(a, b, tris, use);
}

P3 sub(const P3& x, const P3& y) { return {x[0] - y[0], x[1] - y[1], x[2] - y[2]}; }
double dot(const P3& x, const P3& y) { return x[0] * y[0] + x[1] * y[1] + x[2] * y[2]; }
P3 normal(const P3& p0, const P3& p1, const P3& p2) {  // twice the area, along the normal
  const P3 u = sub(p1, p0), v = sub(p2, p0);
  return {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
}

// After the collapse (`into`: removed vertex -> survivor; `moved`: survivor -> its new
// position), does any face that survives and moved flip (normal turned by more than
// acos(min_cos)), or degenerate (twice its area below 1e-6 of its longest edge squared)?
bool any_face_flips(const std::vector<Tri>& tris, const std::vector<P3>& pos,
                    const std::map<uint32_t, uint32_t>& into, const std::map<uint32_t, P3>& moved,
                    double min_cos) {
  for (const Tri& t : tris) {
    Tri after = t;
    for (uint32_t& c : after)
      if (into.count(c)) c = into.at(c);
    if (after[0] == after[1] || after[1] == after[2] || after[0] == after[2]) continue;  // gone
    std::array<P3, 3> old_p, new_p;
    bool around = false;  // a face of an end of the edge
    for (int k = 0; k < 3; ++k) {
      old_p[k] = pos[t[k]];
      new_p[k] = moved.count(after[k]) ? moved.at(after[k]) : pos[after[k]];
      around |= into.count(t[k]) || moved.count(t[k]);
    }
    if (!around) continue;  // its corners stay where they are: same normal
    const P3 n_old = normal(old_p[0], old_p[1], old_p[2]);
    const P3 n_new = normal(new_p[0], new_p[1], new_p[2]);
    double longest2 = 0;
    for (int k = 0; k < 3; ++k) {
      const P3 d = sub(new_p[(k + 1) % 3], new_p[k]);
      longest2 = std::max(longest2, dot(d, d));
    }
    if (longest2 == 0 || dot(n_new, n_new) <= 1e-12 * longest2 * longest2) return true;
    if (dot(n_old, n_old) > 0 &&
        dot(n_old, n_new) <= min_cos * std::sqrt(dot(n_old, n_old) * dot(n_new, n_new)))
      return true;
  }
  return false;
}

// The link condition on the welded surface (each position group one vertex): the edge's
// own triangles are the only contact between the two groups, and the groups have exactly
// `expected` common neighbours.
bool welded_ok(const std::vector<Tri>& tris, const std::vector<uint32_t>& group, uint32_t a, uint32_t b,
               const std::set<Edge>& allowed, size_t expected) {
  const uint32_t ga = group[a], gb = group[b];
  std::set<uint32_t> na, nb;
  for (const Tri& t : tris)
    for (int k = 0; k < 3; ++k)
      for (int j = 0; j < 3; ++j) {
        if (j == k) continue;
        const uint32_t gx = group[t[k]], gy = group[t[j]];
        if (gx == ga && gy == gb && !allowed.count(edge(t[k], t[j]))) return false;
        if (gx == ga && gy != gb && gy != ga) na.insert(gy);
        if (gx == gb && gy != ga && gy != gb) nb.insert(gy);
      }
  std::vector<uint32_t> common;
  std::set_intersection(na.begin(), na.end(), nb.begin(), nb.end(), std::back_inserter(common));
  return common.size() == expected;
}

struct Surface {
  std::vector<Tri> tris;          // live triangles
  std::vector<P3> pos;            // per vertex
  std::vector<uint32_t> group;    // per vertex: its position group (itself when alone)
  std::vector<uint32_t> twin;     // per vertex: the other member of a group of two, or kOmega
  bool twins = false;             // some group has two members or more
  size_t faces = 0, target = 0;
  double min_cos = 0;
};

size_t triangles_on(const std::vector<Tri>& tris, uint32_t a, uint32_t b) {
  size_t n = 0;
  for (const Tri& t : tris) n += has(t, a) && has(t, b);
  return n;
}

// May b collapse into a with the survivor at np?
Verdict collapse(const Surface& s, uint32_t a, uint32_t b, const P3& np) {
  const size_t k = triangles_on(s.tris, a, b);
  if (k == 0) return Verdict::NotEdge;
  const bool seam = s.twin[a] != kOmega && s.twin[b] != kOmega;
  if (!seam) {
    if (k > 2 || k > s.faces - s.target) return Verdict::Refused;
    if (!link_condition(a, b, s.tris)) return Verdict::Refused;
    if (any_face_flips(s.tris, s.pos, {{b, a}}, {{a, np}}, s.min_cos)) return Verdict::Refused;
    if (s.twins && !welded_ok(s.tris, s.group, a, b, {edge(a, b)}, k)) return Verdict::Refused;
    return Verdict::Ok;
  }
  // Along a seam: both sides at once, each side's edge a border edge.
  const uint32_t pa = s.twin[a], pb = s.twin[b];
  const size_t k2 = triangles_on(s.tris, pa, pb);
  if (k != 1 || k2 != 1 || s.faces < s.target + 2) return Verdict::Refused;
  if (!link_condition(a, b, s.tris) || !link_condition(pa, pb, s.tris)) return Verdict::Refused;
  if (any_face_flips(s.tris, s.pos, {{b, a}, {pb, pa}}, {{a, np}, {pa, np}}, s.min_cos)) return Verdict::Refused;
  if (!welded_ok(s.tris, s.group, a, b, {edge(a, b), edge(pa, pb)}, 2)) return Verdict::Refused;
  return Verdict::Ok;
}

}  // namespace oracle

// ---------------------------------------------------------------------------------------
// Test meshes.

// Moves every vertex by up to `amount` in each coordinate (no flat neighbourhoods).
void jitter(Mesh& m, double amount, std::mt19937& rng) {
  std::uniform_real_distribution<float> u(-1.f, 1.f);
  for (float& x : m.positions) x += float(amount) * u(rng);
}

// Drops the triangles whose centroid lies in one of a few separated square holes.
Mesh with_holes(const Mesh& m, double size, int n) {
  Mesh out = m;
  out.triangles.clear();
  const double cell = size / n;
  for (size_t t = 0; t < m.triangle_count(); ++t) {
    double c[2] = {0, 0};
    for (int k = 0; k < 3; ++k)
      for (int d = 0; d < 2; ++d) c[d] += m.positions[3 * m.triangles[3 * t + k] + d] / 3;
    bool in_hole = false;
    for (double hx : {-0.25 * size, 0.25 * size})
      for (double hy : {-0.2 * size, 0.3 * size})
        in_hole |= std::abs(c[0] - hx) < cell && std::abs(c[1] - hy) < cell;
    if (!in_hole) out.triangles.insert(out.triangles.end(), &m.triangles[3 * t], &m.triangles[3 * t + 3]);
  }
  return out;
}

// Cuts the mesh along the vertices with x == 0 (a grid line): the triangles with centroid
// x > 0 get twins of those vertices (same position), recorded in position_vertex.
Mesh with_seam(const Mesh& m) {
  Mesh out = m;
  const size_t nv = m.vertex_count();
  std::vector<uint32_t> twin(nv, UINT32_MAX);
  out.position_vertex.resize(nv);
  for (size_t v = 0; v < nv; ++v) out.position_vertex[v] = uint32_t(v);
  for (size_t t = 0; t < m.triangle_count(); ++t) {
    double cx = 0;
    for (int k = 0; k < 3; ++k) cx += m.positions[3 * m.triangles[3 * t + k]] / 3;
    if (cx <= 0) continue;
    for (int k = 0; k < 3; ++k) {
      const uint32_t v = m.triangles[3 * t + k];
      if (m.positions[3 * v] != 0.f) continue;
      if (twin[v] == UINT32_MAX) {
        twin[v] = uint32_t(out.vertex_count());
        out.positions.insert(out.positions.end(), &m.positions[3 * v], &m.positions[3 * v + 3]);
        out.position_vertex.push_back(v);
      }
      out.triangles[3 * t + k] = twin[v];
    }
  }
  return out;
}

// Jitter that keeps x == 0 exact (the seam's grid line) and y, z free.
void jitter_off_seam(Mesh& m, double amount, std::mt19937& rng) {
  std::uniform_real_distribution<float> u(-1.f, 1.f);
  for (size_t v = 0; v < m.vertex_count(); ++v)
    for (int d = 0; d < 3; ++d) {
      const float j = float(amount) * u(rng);
      if (d == 0 && m.positions[3 * v] == 0.f) continue;
      if (d == 0 && std::abs(m.positions[3 * v]) <= float(amount)) continue;  // keep the side
      m.positions[3 * v + d] += j;
    }
}

struct Case {
  const char* name;
  Mesh mesh;
};

std::vector<Case> test_meshes() {
  std::mt19937 rng(7);
  std::vector<Case> cases;
  cases.push_back({"icosahedron", make_sphere(1.0, 0)});
  cases.push_back({"sphere", make_sphere(1.0, 1)});
  Mesh bumpy = make_sphere(1.0, 2);
  jitter(bumpy, 0.05, rng);
  cases.push_back({"jittered sphere", bumpy});
  Mesh plane = make_plane_with_bump(2.0, 10, 0.5, 0.4);
  jitter(plane, 0.04, rng);
  cases.push_back({"plane (border)", plane});
  cases.push_back({"plane with holes", with_holes(plane, 2.0, 10)});
  Mesh cube = make_cube(4);
  jitter_off_seam(cube, 0.1, rng);
  cases.push_back({"cube with a seam loop", with_seam(cube)});
  Mesh sheet = make_plane_with_bump(2.0, 8, 0.5, 0.4);
  jitter_off_seam(sheet, 0.05, rng);
  cases.push_back({"plane with a seam to the border", with_seam(sheet)});
  return cases;
}

const char* name(oracle::Verdict v) {
  return v == oracle::Verdict::Ok ? "ok" : v == oracle::Verdict::NotEdge ? "not an edge" : "refused";
}
oracle::Verdict verdict(detail::Check c) {
  using detail::Check;
  return c == Check::Ok ? oracle::Verdict::Ok : c == Check::NotEdge ? oracle::Verdict::NotEdge : oracle::Verdict::Refused;
}

// The oracle's view of the simplifier's state: live triangles, positions, groups.
oracle::Surface surface_of(const detail::State& s, const Mesh& in, double min_cos) {
  oracle::Surface o;
  for (size_t t = 0; t < s.fans.triangle_count(); ++t)
    if (s.fans.live[t])
      o.tris.push_back({s.fans.corners[3 * t], s.fans.corners[3 * t + 1], s.fans.corners[3 * t + 2]});
  o.pos.resize(s.nv);
  for (size_t v = 0; v < s.nv; ++v) o.pos[v] = {s.vert[v].p[0], s.vert[v].p[1], s.vert[v].p[2]};
  o.group.resize(s.nv);
  o.twin.assign(s.nv, oracle::kOmega);
  std::map<uint32_t, std::vector<uint32_t>> members;
  for (size_t v = 0; v < s.nv; ++v) {
    o.group[v] = in.position_vertex.empty() ? uint32_t(v) : s.inv[in.position_vertex[s.order[v]]];
    members[o.group[v]].push_back(uint32_t(v));
  }
  for (auto& [g, list] : members) {
    o.twins |= list.size() > 1;
    if (list.size() == 2) o.twin[list[0]] = list[1], o.twin[list[1]] = list[0];
  }
  o.faces = s.faces;
  o.target = s.target;
  o.min_cos = min_cos;
  return o;
}

}  // namespace

TEST_CASE("collapse check agrees with a set-based oracle on random collapses", "[simplify][oracle]") {
  size_t compared = 0, ok = 0, refused = 0, not_edge = 0, seam_compared = 0;
  for (const Case& c : test_meshes()) {
    for (double min_cos : {0.0, 0.5}) {
      for (unsigned seed : {1u, 2u}) {
        std::mt19937 rng(seed);
        SimplifyOptions opt;
        opt.target_faces = std::max<size_t>(2, c.mesh.triangle_count() / 8);
        opt.min_normal_cos = min_cos;
        detail::State s;
        s.init(c.mesh, opt, nullptr, nullptr);
        for (int step = 0; step < 400 && s.faces > s.target; ++step) {
          const oracle::Surface o = surface_of(s, c.mesh, min_cos);
          std::uniform_int_distribution<size_t> pick_tri(0, o.tris.size() - 1);
          std::uniform_int_distribution<int> pick(0, 2);
          std::uniform_real_distribution<double> u(-1, 1);
          for (int trial = 0; trial < 6; ++trial) {
            const oracle::Tri& t = o.tris[pick_tri(rng)];
            const int k = pick(rng);
            uint32_t a = t[k], b = t[(k + 1) % 3];
            if (trial == 5) b = uint32_t(std::uniform_int_distribution<size_t>(0, s.nv - 1)(rng));  // often no edge
            if (a == b) continue;
            // The survivor's place: the cost's, an end, the midpoint, or somewhere near.
            double np[3];
            for (int d = 0; d < 3; ++d) np[d] = 0.5 * (s.p(a)[d] + s.p(b)[d]);
            s.cost(a, b, np);  // two locked ends off a seam: no place, the midpoint stays
            const int where = pick(rng) + (trial & 1) * 3;
            const double* pa = s.p(a);
            const double* pb = s.p(b);
            for (int d = 0; d < 3; ++d) {
              const double len = std::abs(pb[d] - pa[d]) + 0.02;
              if (where == 1) np[d] = pa[d];
              if (where == 2) np[d] = 0.5 * (pa[d] + pb[d]);
              if (where >= 3) np[d] = 0.5 * (pa[d] + pb[d]) + (where - 2) * len * u(rng);
            }
            const oracle::Verdict want = oracle::collapse(o, a, b, {np[0], np[1], np[2]});
            const oracle::Verdict got = verdict(s.check_edge(a, b, np));
            const bool seam = o.twin[a] != oracle::kOmega && o.twin[b] != oracle::kOmega;
            INFO(c.name << ", min_cos " << min_cos << ", seed " << seed << ", step " << step << ": " << b
                        << " into " << a << (seam ? " (seam edge)" : "") << ", faces " << s.faces
                        << ", oracle " << name(want) << ", check " << name(got));
            if (seam)  // a seam pair that is no edge on one side reads as refused or no edge
              CHECK((got == oracle::Verdict::Ok) == (want == oracle::Verdict::Ok));
            else
              CHECK(got == want);
            ++compared;
            seam_compared += seam;
            ok += want == oracle::Verdict::Ok;
            refused += want == oracle::Verdict::Refused;
            not_edge += want == oracle::Verdict::NotEdge;
          }
          // Simplify on: a random edge at its cost's place, when the check allows it.
          const oracle::Tri& t = o.tris[pick_tri(rng)];
          const int k = pick(rng);
          const uint32_t a = std::min(t[k], t[(k + 1) % 3]), b = std::max(t[k], t[(k + 1) % 3]);
          if (s.both_locked(a, b)) continue;
          double np[3];
          const double cost = s.cost(a, b, np);
          if (s.check_edge(a, b, np) != detail::Check::Ok) continue;
          uint32_t kept[2], removed[2];
          s.apply(a, b, np, cost, kept, removed);
        }
      }
    }
  }
  INFO(compared << " compared: " << ok << " ok, " << refused << " refused, " << not_edge << " not an edge, "
                << seam_compared << " along seams");
  // The comparison means something only if every outcome came up often.
  CHECK(ok > 500);
  CHECK(refused > 500);
  CHECK(not_edge > 100);
  CHECK(seam_compared > 50);
}
