// meshsal (internal): the simplifier's collapses and its output, see simplify_state.h.
#include "simplify/simplify_state.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/mesh_context.h"
#include "core/model_frame.h"

namespace meshsal {
namespace detail {

int State::apply(uint32_t a, uint32_t b, const double np[3], double cost, uint32_t kept[2],
                 uint32_t removed[2]) {
  reached_error2 = std::max(reached_error2, error2(a, b, np, cost));
  if (seams.seam_edge(a, b)) {
    const double* pb = p(b);
    if (np[0] == pb[0] && np[1] == pb[1] && np[2] == pb[2]) std::swap(a, b);  // b's end stays
    kept[0] = a, removed[0] = b, kept[1] = seams.partner[a], removed[1] = seams.partner[b];
    collapse(a, b, np, cost);
    collapse(kept[1], removed[1], np, cost);
    return 2;
  }
  if (has_locks && locked[b]) std::swap(a, b);
  kept[0] = a, removed[0] = b;
  collapse(a, b, np, cost);
  return 1;
}

void State::collapse(uint32_t a, uint32_t b, const double np[3], double c) {
  if (!attributes.empty() && !(has_locks && locked[a])) attributes.carry(a, b, p(a), p(b), np);
  if (seams.has_twins) seams.note_collapse(fans, a, b);
  for (int k = 0; k < 3; ++k) vert[a].p[k] = np[k];
  vert[a].q += vert[b].q;
  vert[a].plane_weight += vert[b].plane_weight;
  if (!plain.empty()) plain[a] += plain[b];
  if (border[a] && border[b]) --border_vertices;
  border[a] = border[a] | border[b];
  faces -= fans.merge(a, b, alive);
  alive[b] = 0;
  ++collapses;
  changed[a] = uint32_t(collapses);
  changed[b] = UINT32_MAX;
  if (record) sequence.push_back({order[a], order[b], c});
}

bool State::joins_pins(uint32_t kept, uint32_t removed) const {
  for (uint32_t t : fans.fan(removed)) {
    if (!fans.live[t]) continue;
    for (int k = 0; k < 3; ++k) {
      const uint32_t x = fans.corners_of(t)[k];
      if (x == removed || x == kept || !pin[x]) continue;
      bool linked = false;
      for (uint32_t u : fans.fan(kept)) {
        if (!fans.live[u]) continue;
        const uint32_t* c = fans.corners_of(u);
        linked |= c[0] == x || c[1] == x || c[2] == x;
      }
      if (!linked) return true;
    }
  }
  return false;
}

Mesh State::output(SimplifyReport* report) const {
  std::vector<uint32_t> remap(nv, UINT32_MAX);
  Mesh out;
  std::vector<uint32_t> origin;
  const std::vector<uint32_t>& tri = fans.corners;
  const std::vector<uint8_t>& tri_alive = fans.live;
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
  copy_mesh_context(*mesh_in, out);
  if (!tri_material.empty()) {
    out.triangle_material.reserve(out.triangle_count());
    for (size_t t = 0; t < tri_alive.size(); ++t)
      if (tri_alive[t]) out.triangle_material.push_back(tri_material[t]);
  }
  attributes.write(*mesh_in, origin, inv, changed, &out);
  write_position_vertex(*mesh_in, origin, &out);
  carry_model_frame(*mesh_in, origin, out);  // an unmoved survivor is written as it was read
  if (report) {
    report->input_faces = tri_alive.size();
    report->target_faces = target;
    report->output_faces = out.triangle_count();
    report->output_vertices = out.vertex_count();
    report->reached = report->output_faces == target;
    report->unchanged = false;
    report->note.clear();
    // (A tile's own mesh is no whole: its caller warns for the whole mesh, once.)
    report->warning = pinned ? std::string() : precision_warning(*mesh_in);
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
    report->collapses = collapses;
    report->vertex_origin = std::move(origin);
  }
  return out;
}

}  // namespace detail
}  // namespace meshsal
