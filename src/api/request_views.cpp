// meshsal: the views of a request: the best view (the one view pipeline, best_viewpoint), the
// picture of a view (titled, or beside two simplified meshes), the view map, the page.
#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include "api/request_parts.h"
#include "core/mesh_points.h"
#include "meshsal/meshsal.h"
#include "view/compare_picture.h"
#include "view/legend.h"
#include "view/map_picture.h"
#include "view/picture.h"

namespace meshsal {
namespace {

std::string number(double x) {
  char b[64];
  std::snprintf(b, sizeof b, "%.4g", x);
  return b;
}

// The statistics table of a page: what the model is and what its saliency came to.
std::vector<std::pair<std::string, std::string>> page_stats(const Mesh& mesh, const std::vector<double>& s,
                                                            const std::string& source, double seconds) {
  double lo = 0, hi = 0, sum = 0;
  size_t n = 0;
  const std::vector<uint8_t> used = referenced_vertices(mesh);
  for (size_t v = 0; v < s.size(); ++v)
    if (used[v]) {
      lo = n ? std::min(lo, s[v]) : s[v], hi = n ? std::max(hi, s[v]) : s[v];
      sum += s[v], ++n;
    }
  return {{"vertices", std::to_string(mesh.vertex_count())},
          {"faces", std::to_string(mesh.triangle_count())},
          {"saliency", source},
          {"S min / mean / max", number(lo) + " / " + number(n ? sum / double(n) : 0) + " / " + number(hi)},
          {"computed in", number(seconds) + " s"}};
}

// "saliency" or "|mean curvature|", as the pictures name their score.
std::string score_name(Score score) { return score == Score::Saliency ? "saliency" : "|mean curvature|"; }

}  // namespace

void make_views(RequestRun& run) {
  const Request& r = run.request;
  RequestResult& out = run.result;
  const Mesh& mesh = *run.plain;
  const std::string name = file_name_of(r.input);
  const bool scored = !r.grey || r.find_view || !r.page_output.empty() || !r.map_output.empty();
  if (scored) view_score(run);
  out.view = r.view;
  if (r.find_view || !r.page_output.empty() || !r.map_output.empty()) {
    ViewpointOptions vo = r.viewpoint;
    if (!vo.optimiser.cancel) vo.optimiser.cancel = r.saliency.cancel;
    if (!r.map_output.empty() && vo.views == 0) vo.views = 2000;
    out.viewpoint = best_viewpoint(mesh, out.score, vo);
    out.view = out.viewpoint.view;
    if (!out.viewpoint.note.empty()) add_note(run, out.viewpoint.note);
  }
  if (!r.picture_output.empty()) {
    const std::vector<double>* shown = r.grey ? nullptr : &out.score;
    RenderStyle style = r.style;
    Image picture;
    if (r.compare.empty()) {
      VisibleScore visible;
      picture = titled_view(mesh, shown, out.view, style, name, score_name(r.score), &visible);
      out.visible_score = visible.U, out.visible_total = visible.total;
    } else {
      LoadOptions o = r.load;
      const Mesh plain = load_mesh(r.compare[0], o);
      const Mesh salient = load_mesh(r.compare[1], o);
      // Each panel is labelled with its file's name.
      picture = compare_picture(mesh, shown, plain, salient, out.view, style, name, file_name_of(r.compare[0]),
                                file_name_of(r.compare[1]));
      if (shown) {
        const VisibleScore visible = picture_visible_score(mesh, out.score, out.view, style.up);
        out.visible_score = visible.U, out.visible_total = visible.total;
      }
    }
    write_png(r.picture_output, picture);
    out.picture_width = picture.width, out.picture_height = picture.height;
    out.outputs.push_back(r.picture_output);
  }
  if (!r.map_output.empty()) {
    const ViewMap& map = out.viewpoint.map;
    char ring[96], cross[96];
    std::snprintf(ring, sizeof ring, "exhaustive maximum (%d views), U = %s", int(map.views.size()),
                  value_text(map.U[map.best]).c_str());
    std::snprintf(cross, sizeof cross, "optimiser's result, U = %s", value_text(out.viewpoint.U).c_str());
    static const char* const up_names[] = {"y", "-y", "z", "-z", "x", "-x"};
    write_png(r.map_output, view_map_picture(map, r.map_width, map.views[map.best], ring, out.viewpoint.view, cross,
                                             name + ": visible " + score_name(r.score) + " by view direction (--up " +
                                                 up_names[int(r.viewpoint.up)] + ")"));
    out.outputs.push_back(r.map_output);
  }
  if (!r.page_output.empty()) {
    ViewPageOptions po = r.page;
    if (po.title.empty()) po.title = name;
    if (po.stats.empty()) po.stats = page_stats(mesh, out.score, out.saliency_source, run.timer_seconds());
    // The view's numbers as `meshsal viewpoint` reports them.
    if (po.visible_score < 0) po.visible_score = out.viewpoint.U, po.visible_fraction = out.viewpoint.visible_fraction;
    out.page = write_view_page(r.page_output, mesh, out.score, out.viewpoint.camera, po);
    out.outputs.push_back(r.page_output);
    if (out.page.simplified)
      add_note(run, out.page.within_max_faces
                        ? "the page shows a copy simplified to " + std::to_string(out.page.shown_faces) + " faces (the mesh has " +
                              std::to_string(mesh.triangle_count()) + ")"
                        : "the page shows a copy simplified to " + std::to_string(out.page.shown_faces) + " faces, not the " +
                              std::to_string(po.max_faces) + " of --max-faces: the simplifier could go no further (the mesh has " +
                              std::to_string(mesh.triangle_count()) + ")");
  }
}

}  // namespace meshsal
