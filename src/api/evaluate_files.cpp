// meshsal: `meshsal eval PRED GT` and Python's evaluate(pred, gt) as one library call: the
// prediction read from a mesh's scalar attribute, the ground truth from a mesh or text rows,
// brought to PRED's vertices (same vertices, joined by position, or --transfer nearest),
// scored raw and, with smoothing, smoothed beside it (evaluate_scores).
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "core/mesh_points.h"
#include "core/model_frame.h"
#include "core/number_text.h"
#include "meshsal/meshsal.h"

namespace meshsal {
namespace {

// The file's name without a trailing .gz: what decides mesh or text.
bool is_mesh_name(const std::string& path) {
  std::string name = path;
  if (name.size() > 3 && (name.compare(name.size() - 3, 3, ".gz") == 0 || name.compare(name.size() - 3, 3, ".GZ") == 0))
    name.resize(name.size() - 3);
  return mesh_format(name) != nullptr;
}

// The per-vertex scalar `name` of a mesh read from `path` (`option` names the option that
// picks another), every value finite.
std::vector<double> attribute_values(const Mesh& mesh, const std::string& path, const std::string& name,
                                     const char* option) {
  const VertexAttribute* found = nullptr;
  std::string names;
  for (const VertexAttribute& a : mesh.attributes) {
    if (a.name == name) found = &a;
    names += (names.empty() ? "" : ", ") + a.name;
  }
  if (!found)
    throw Error(path + ": no per-vertex attribute '" + name + "' (" +
                (names.empty() ? std::string("it has none") : "it has: " + names) + "; " + option +
                " names another; S is PLY's quality or glTF's _SALIENCY)");
  std::vector<double> out(found->values.begin(), found->values.end());
  for (size_t v = 0; v < out.size(); ++v)
    if (!std::isfinite(out[v]))
      throw Error(path + ": attribute '" + name + "' of vertex " + std::to_string(v) + " is " + number_text(out[v], 9));
  return out;
}

// Throws unless `gt` has the vertices of `pred`: the same count, each at the same position
// within 1e-6 of the diagonal (model coordinates).
void check_same_vertices(const Mesh& pred, const Mesh& gt, const std::string& gt_path, double diagonal) {
  const std::string hint = ": not PRED's vertices (--transfer nearest carries the ground truth to them)";
  if (gt.vertex_count() != pred.vertex_count())
    throw Error(gt_path + ": " + std::to_string(gt.vertex_count()) + " vertices, PRED has " +
                std::to_string(pred.vertex_count()) + hint);
  const double tol = 1e-6 * diagonal;
  for (size_t v = 0; v < pred.vertex_count(); ++v) {
    double a[3], b[3];
    model_position(gt, v, a);
    model_position(pred, v, b);
    const double d = std::sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
    if (!(d <= tol))
      throw Error(gt_path + ": vertex " + std::to_string(v) + " is at (" + number_text(a[0], 9) + ", " + number_text(a[1], 9) +
                  ", " + number_text(a[2], 9) + "), in PRED at (" + number_text(b[0], 9) + ", " + number_text(b[1], 9) + ", " +
                  number_text(b[2], 9) + ")" + hint);
  }
}

std::string lines_text(const std::vector<size_t>& lines, size_t total) {
  std::string s;
  for (size_t l : lines) s += (s.empty() ? "" : ", ") + std::to_string(l);
  if (total > lines.size()) s += ", ...";
  return s;
}

}  // namespace

EvalReport evaluate_files(const std::string& pred_path, const std::string& gt_path, const EvalOptions& options) {
  if (!(options.smooth >= 0 && options.smooth <= 0.5))
    throw Error("the smoothing sigma must be in (0, 0.5] of the bounding-box diagonal (0: none), got " +
                number_text(options.smooth, 9));
  if (options.gt_column != 0 && options.gt_column < 4)
    throw Error("the ground truth's value column must be 4 or more (x y z come first), got " +
                std::to_string(options.gt_column));
  if (!is_mesh_name(pred_path))
    throw Error(pred_path + ": PRED must be a mesh file (.ply, .gltf, .glb, ...) with a per-vertex scalar");
  LoadOptions lo;
  lo.attributes = true;  // PLY properties, glTF scalars (_SALIENCY as quality)
  lo.max_input_bytes = options.max_input_bytes;
  const Mesh pred = load_mesh(pred_path, lo);
  const std::vector<double> p = attribute_values(pred, pred_path, options.attribute, "--attribute");
  const size_t n = pred.vertex_count();

  EvalReport report;
  report.vertices = n;
  report.diagonal = mesh_points_bbox(pred, referenced_vertices(pred)).diagonal();
  std::vector<double> g(n, 0.0);
  std::vector<uint8_t> has(n, 1);
  const bool nearest = options.transfer == EvalTransfer::Nearest;
  if (!is_mesh_name(gt_path)) {
    report.gt_is_text = true;
    const VertexRows rows = read_vertex_rows(gt_path, options.gt_column, options.max_input_bytes);
    report.gt_column = options.gt_column ? options.gt_column : int(rows.columns);
    report.gt_rows = rows.values.size();
    if (nearest) {
      const NearestValues t = transfer_nearest(rows.xyz, rows.values, pred);
      g = t.values;
      report.transferred = true;
      report.transfer_max_distance = t.max_distance, report.transfer_mean_distance = t.mean_distance;
      report.matched_rows = report.gt_rows;
    } else {
      const JoinedRows j = join_vertex_rows(pred, rows);
      g = j.values;
      has = j.has_value;
      report.matched_rows = j.matched_rows;
      report.unmatched_rows = j.unmatched_rows;
      report.unmatched_lines = j.unmatched_lines;
      report.vertices_without_gt = j.vertices_without_value;
      if (j.unmatched_rows)
        report.notes.push_back(std::to_string(j.unmatched_rows) + " of " + std::to_string(j.rows) +
                               " ground-truth rows matched no vertex of PRED within 1e-6 of its diagonal and were left "
                               "out (lines " + lines_text(j.unmatched_lines, j.unmatched_rows) +
                               "); --transfer nearest carries rows to the nearest vertex instead");
      if (j.vertices_without_value)
        report.notes.push_back(std::to_string(j.vertices_without_value) + " of PRED's " + std::to_string(n) +
                               " vertices have no ground-truth row and are not scored");
    }
  } else {
    const Mesh gt = load_mesh(gt_path, lo);
    report.gt_vertices = gt.vertex_count();
    const std::vector<double> gv = attribute_values(gt, gt_path, options.gt_attribute, "--gt-attribute");
    if (nearest) {
      const NearestValues t = transfer_nearest(model_positions(gt), gv, pred);
      g = t.values;
      report.transferred = true;
      report.transfer_max_distance = t.max_distance, report.transfer_mean_distance = t.mean_distance;
    } else {
      check_same_vertices(pred, gt, gt_path, report.diagonal);
      g = gv;
    }
  }

  std::vector<double> ps, gs;
  for (size_t v = 0; v < n; ++v)
    if (has[v]) ps.push_back(p[v]), gs.push_back(g[v]);
  if (ps.size() < 2)
    throw Error("only " + std::to_string(ps.size()) + " of PRED's " + std::to_string(n) +
                " vertices have ground truth: scoring needs at least 2" +
                (report.unmatched_rows ? " (" + std::to_string(report.unmatched_rows) +
                                             " rows matched no vertex; --transfer nearest carries them)"
                                       : std::string()));
  report.raw = evaluate_scores(ps, gs);
  if (options.smooth > 0) {
    const std::vector<double> smoothed = smooth_vertex_values(pred, p, options.smooth, options.threads);
    report.smooth_sigma = options.smooth * report.diagonal;
    std::vector<double> ss;
    for (size_t v = 0; v < n; ++v)
      if (has[v]) ss.push_back(smoothed[v]);
    report.smoothed = evaluate_scores(ss, gs);
  }
  return report;
}

}  // namespace meshsal
