// meshsal: Garland-Heckbert edge-collapse simplification over flat arrays.
// The state (simplify_state.h) costs, checks and makes collapses; here two ways to pick the
// next one: a lazily invalidated queue of edges (simplify_mesh) and a full scan
// (simplify_bruteforce, the queue's test oracle: it shares the cost, check and collapse,
// so it catches ordering bugs only; collapse_check's own oracle is in the tests).
#include "simplify/simplify.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "meshsal/meshsal.h"
#include "core/cancel.h"
#include "core/timer.h"
#include "simplify/collapse_queue.h"
#include "simplify/edge_queue.h"
#include "simplify/simplify_state.h"
#include "simplify/triangle_bits.h"

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

using namespace detail;

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

// After a collapse into a: the refused edges of a and of its new 1-ring count again (and,
// for a twin, those of its twins: their edges depend on its neighbourhood through the
// welded link condition), and every edge of a gets a fresh entry.
void refresh(State& s, CollapseQueue& queue, uint32_t a, std::vector<uint32_t>& ring) {
  const auto current = [&](const Entry& x) { return s.current(x); };
  const auto release = [&](uint32_t w) {
    queue.release(w, current);
    if (s.seams.has_twins && s.seams.twin_next[w] != SeamGroups::NONE)
      for (uint32_t x = s.seams.twin_next[w]; x != w; x = s.seams.twin_next[x]) queue.release(x, current);
  };
  const uint32_t now = uint32_t(s.collapses), stamp = s.marks.new_stamps(1);
  uint32_t* const mark = s.marks.mark.data();
  // The new 1-ring of a; its quadrics are scattered in memory: prefetch them together.
  mark[a] = stamp;
  const uint32_t* tl = s.fans.fan_begin(a);
  const uint32_t n = s.fans.fan_size(a);
  if (ring.size() < 2 * size_t(n) + 1) ring.resize(2 * size_t(n) + 1);
  size_t nring = 0;
  for (uint32_t i = 0; i < n; ++i) {
    const uint32_t* tv = s.fans.corners_of(tl[i]);
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
    queue.push(make_entry(s.cost(lo, hi, tmp), lo, hi, now));
  }
}

// The data of the next pick, while this one is worked on. Always inlined: GCC finds a
// function of prefetches alone 'pure' (no stores) and, left a call, deletes it as unused.
__attribute__((always_inline)) inline void prefetch_ends(const State& s, const Entry& n) {
  __builtin_prefetch(&s.changed[n.a]);
  __builtin_prefetch(&s.changed[n.b]);
  __builtin_prefetch(&s.fans.place[n.a]);
  __builtin_prefetch(&s.fans.place[n.b]);
  __builtin_prefetch(&s.vert[n.a]);
  __builtin_prefetch(&s.vert[n.b]);
  __builtin_prefetch(reinterpret_cast<const char*>(&s.vert[n.a]) + 64);
  __builtin_prefetch(reinterpret_cast<const char*>(&s.vert[n.b]) + 64);
}

}  // namespace

// Invariant of the loop below: every current edge that is not refused has a current entry
// in the queue, with its key; stale entries (an end collapsed or moved since) are skipped.
// So the first current entry popped is the edge that a full scan would pick. A refused
// edge waits in the refused lists of its ends until a collapse changes the 1-ring of one
// of them; then its entry goes back into the queue.
Simplified simplify_mesh(const Mesh& mesh, const SimplifyOptions& options,
                         const std::vector<double>& vertex_weights) {
  if (options.tiles > 1)
    throw Error("simplify_mesh does not tile (options.tiles " + std::to_string(options.tiles) +
                "): simplify_mesh_tiled does");
  Simplified r;
  r.mesh = simplify_pinned(mesh, options, vertex_weights.empty() ? nullptr : &vertex_weights, nullptr, &r.report);
  return r;
}

Mesh simplify_pinned(const Mesh& mesh, const SimplifyOptions& options, const std::vector<double>* vertex_weights,
                     const std::vector<uint8_t>* pinned, SimplifyReport* report) {
  if (simplify_keeps_mesh(options, mesh.triangle_count())) return unchanged_mesh(mesh, report);
  const CancelScope cancel(options.cancel);
  const Timer t0;
  State s;
  s.pinned = pinned;
  std::vector<Entry> initial;
  s.init(mesh, options, vertex_weights, &initial);
  CollapseQueue queue(s.nv);
  for (const Entry& x : initial)
    if (!s.both_locked(x.a, x.b)) queue.push(x);
  std::vector<Entry>().swap(initial);
  queue.start();
  EdgeQueue& edges = queue.edges();
  const auto current = [&](const Entry& x) { return s.current(x); };
  std::vector<uint32_t> ring;
  double np[3];
  size_t polls = 0;
  while (s.faces > s.target) {
    if ((++polls & 4095) == 0) throw_if_cancelled();
    // One face short on a closed manifold surface: every collapse removes two faces and
    // would overshoot, so the scan below would refuse every edge left. Stop now instead
    // (same result; the report's note says why).
    if (s.faces == s.target + 1 && s.border_vertices == 0) break;
    queue.sweep_if_grown(current);
    if (!edges.ready(current)) break;
    const Entry e = edges.pop();
    if (edges.has_top()) prefetch_ends(s, edges.top());
    if (!s.current(e)) continue;
    const double exact = s.cost(e.a, e.b, np);
    const Check c = s.over_error(e.a, e.b, np, exact) ? Check::Refused : s.check_edge(e.a, e.b, np);
    if (c != Check::Ok) {
      ++s.refused;
      queue.refuse(e);
      continue;
    }
    uint32_t kept[2], removed[2];
    const int made = s.apply(e.a, e.b, np, exact, kept, removed);
    for (int i = 0; i < made; ++i) queue.forget(removed[i]);
    for (int i = 0; i < made; ++i) refresh(s, queue, kept[i], ring);
    if (edges.has_top()) {  // the next pick's triangles, for its check
      const Entry& n = edges.top();
      for (uint32_t v : {n.a, n.b})
        for (uint32_t t : s.fans.fan(v)) __builtin_prefetch(s.fans.corners_of(t));
    }
    // A seam edge's cost holds the partners' quadrics: a partner whose twin took a
    // collapse has changed too.
    if (made == 1 && s.seams.pair(kept[0])) {
      const uint32_t w = s.seams.partner[kept[0]];
      s.changed[w] = uint32_t(s.collapses);
      s.fans.compact(w);
      refresh(s, queue, w, ring);
    }
  }
  Mesh out = s.output(report);
  if (report) report->seconds = t0.seconds();
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
    for (size_t t = 0; t < s.fans.triangle_count(); ++t) {
      if (!s.fans.live[t]) continue;
      for (int k = 0; k < 3; ++k) {
        const uint32_t x = s.fans.corners[3 * t + k], y = s.fans.corners[3 * t + (k + 1) % 3];
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
  if (report) report->seconds = t0.seconds();
  return out;
}

}  // namespace meshsal
