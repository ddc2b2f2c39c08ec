// meshsal (internal): the simplifier's state over flat arrays: the input's vertices in
// internal order and coordinates, their quadrics, the triangle fans, borders, locks, seams
// and attributes, and what the collapses made so far. simplify_mesh (a queue of edges) and
// simplify_bruteforce (a full scan) pick the collapses; this state costs, checks and makes
// them.
#pragma once
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "meshsal/meshsal.h"
#include "simplify/attribute_carrier.h"
#include "simplify/collapse_check.h"
#include "simplify/edge_queue.h"
#include "simplify/quadric.h"
#include "simplify/seam_groups.h"
#include "simplify/triangle_fans.h"
#include "simplify/vertex_marks.h"
#include "simplify/vertex_record.h"

namespace meshsal {
namespace detail {

struct State {
  // --- the input, and how internal vertices map to it ---
  const Mesh* mesh_in = nullptr;
  size_t nv = 0;
  // The input's positions (3 per input vertex): a vertex no collapse moved is written back
  // with these exact values, not through the rounding of (p - center) * scale and back.
  const float* input_positions = nullptr;
  double center[3] = {0, 0, 0};
  double scale = 1;                          // internal = (p - center) * scale
  std::vector<uint32_t> order;               // internal vertex id -> input vertex
  std::vector<uint32_t> inv;                 // input vertex -> internal id

  // --- the options ---
  size_t target = 0;                         // face count to reach
  double min_cos = 0;
  bool record = false;                       // record the collapse sequence
  double max_error2 = HUGE_VAL;              // target_error squared (internal units)

  // --- the surface ---
  std::vector<VertexRecord> vert;
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
  TriangleFans fans;
  std::vector<uint32_t> tri_material;        // per triangle when the input has triangle_material
  std::vector<uint8_t> alive;                // per vertex
  std::vector<uint8_t> border;               // on an open border or a non-manifold edge
  size_t border_vertices = 0;                // live vertices with border[] set
  // Locked vertices (seam twins, lock_border, pinned) neither move nor go.
  std::vector<uint8_t> locked;
  // Set before init (may stay null): one flag per input vertex, locked whatever lock_border
  // says (the tiled simplifier's cuts, simplify_tiled.cpp).
  const std::vector<uint8_t>* pinned = nullptr;
  std::vector<uint8_t> pin;  // pinned, per internal vertex (empty when pinned is null)
  bool has_locks = false;
  SeamGroups seams;
  AttributeCarrier attributes;

  // --- the collapses so far ---
  size_t faces = 0;                          // live triangles
  size_t collapses = 0;
  // Collapse count when the vertex last moved; UINT32_MAX once it is collapsed away, so
  // that one 4-byte load per end tells whether an entry is current.
  std::vector<uint32_t> changed;
  double reached_error2 = 0;                 // largest squared error of a collapse made
  size_t error_refused = 0;                  // refusals for the error bound
  size_t refused = 0;                        // refusals of any kind
  std::vector<Collapse> sequence;            // when `record`

  // --- scratch ---
  // Marks for the link condition (the check) and the new ring (after a collapse): one
  // array for both, so that the ring's marks are still in cache.
  VertexMarks marks;
  CollapseCheck checker;

  // Setup, in this order: the input checked and its degenerate triangles dropped;
  // vertices renumbered along a Morton curve in internal coordinates; the triangle fans
  // and plane quadrics; the unique edges with the border quadrics; then the weights, locks,
  // seams, attributes and (edges given) the initial edge costs.
  void init(const Mesh& mesh, const SimplifyOptions& options, const std::vector<double>* w,
            std::vector<Entry>* edges);

  const double* p(uint32_t v) const { return vert[v].p; }

  // The cost of collapsing edge (a, b) and where the survivor goes (out).
  double cost(uint32_t a, uint32_t b, double out[3]) const {
    if (has_locks && (locked[a] | locked[b])) {  // the new vertex stays where the locked one is
      if (locked[a] && locked[b]) return seam_cost(a, b, out);
      const double* k = p(locked[a] ? a : b);
      for (int i = 0; i < 3; ++i) out[i] = k[i];
      return (vert[a].q + vert[b].q).error(k);
    }
    return optimal_placement(vert[a].q + vert[b].q, p(a), p(b), out);
  }
  // Along a seam: both sides' quadrics; the cheaper end stays, on both sides.
  double seam_cost(uint32_t a, uint32_t b, double out[3]) const {
    if (!seams.seam_edge(a, b)) return HUGE_VAL;
    const uint32_t pa = seams.partner[a], pb = seams.partner[b];
    const Quadric q = vert[a].q + vert[pa].q + vert[b].q + vert[pb].q;
    const double ea = q.error(p(a)), eb = q.error(p(b));
    const double* k = eb < ea ? p(b) : p(a);
    for (int i = 0; i < 3; ++i) out[i] = k[i];
    return std::min(ea, eb);
  }
  // No collapse can join two locked vertices: such edges never enter the queue.
  bool both_locked(uint32_t a, uint32_t b) const {
    return has_locks && locked[a] && locked[b] && !seams.seam_edge(a, b);
  }
  // An entry is current while neither end has changed (or died) since its cost was
  // computed. & not &&: no branches, it runs over whole buckets.
  bool current(const Entry& e) const {
    return (changed[e.a] <= e.stamp) & (changed[e.b] <= e.stamp);
  }

  // The collapse's error squared (see SimplifyOptions::target_error): a distance, so with
  // vertex weights it is taken from the unweighted quadrics (a weight near 0 would hide
  // what a collapse costs: a flat region's border cut away read as error 0).
  double error2(uint32_t a, uint32_t b, const double np[3], double cost) const {
    const bool seam = seams.seam_edge(a, b);
    if (plain.empty()) {
      double w = vert[a].plane_weight + vert[b].plane_weight;
      if (seam) w += vert[seams.partner[a]].plane_weight + vert[seams.partner[b]].plane_weight;
      return w > 0 ? cost / w : 0;
    }
    Plain sum = plain[a];
    sum += plain[b];
    if (seam) sum += plain[seams.partner[a]], sum += plain[seams.partner[b]];
    return sum.plane_weight > 0 ? std::max(0.0, sum.q.error(np)) / sum.plane_weight : 0;
  }
  // Refuses a collapse over the error bound (before the costlier check).
  bool over_error(uint32_t a, uint32_t b, const double np[3], double cost) {
    if (!(error2(a, b, np, cost) > max_error2)) return false;
    ++error_refused;
    return true;
  }
  // Whether b may collapse into a with the survivor at np (see collapse_check.h).
  Check check_edge(uint32_t a, uint32_t b, const double np[3]) {
    const CheckSurface s{&fans, vert.data(), border.data(), &seams, &marks, faces, target, min_cos};
    const Check c = checker.edge(s, a, b, np);
    if (c == Check::Ok && !pin.empty() && pin[a] != pin[b] && joins_pins(pin[a] ? a : b, pin[a] ? b : a))
      return Check::Refused;
    return c;
  }
  // Whether `removed` going into the pinned `kept` would join kept to a pinned vertex it
  // has no edge to. Pinned vertices are shared with other tiles, which may make that edge
  // too (a non-manifold edge after the join): so no tile makes one.
  bool joins_pins(uint32_t kept, uint32_t removed) const;
  // check_edge passed: collapses the edge onto its locked end if it has one, else onto a.
  // Returns how many collapses it made (2 along a seam); kept[i] took removed[i].
  int apply(uint32_t a, uint32_t b, const double np[3], double cost, uint32_t kept[2], uint32_t removed[2]);
  // b into a, a moved to np.
  void collapse(uint32_t a, uint32_t b, const double np[3], double cost);

  // The simplified mesh, in input vertex order; fills the report when given.
  Mesh output(SimplifyReport* report) const;

 private:
  void take_input(const Mesh& mesh, const SimplifyOptions& options, const std::vector<double>* w);
  void order_vertices(const Mesh& mesh);
  void build_fans_and_quadrics();
  void build_edges(double border_weight, std::vector<uint32_t>* edge_a, std::vector<uint32_t>* edge_b);
  void take_locks_seams_and_attributes(const Mesh& mesh, bool lock_border);
};

}  // namespace detail
}  // namespace meshsal
