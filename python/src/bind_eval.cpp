// meshsal Python module: evaluate(), a prediction scored against ground truth as `meshsal
// eval` scores it (the library's evaluate_files and evaluate_scores; SPEC section 7).
#include <optional>
#include <string>
#include <vector>

#include <pybind11/stl.h>

#include "arg_values.h"
#include "bindings.h"
#include "meshsal/meshsal.h"
#include "numpy_in.h"
#include "paths.h"

namespace meshsal_py {

namespace {

bool path_like(const py::handle& x) {
  return py::isinstance<py::str>(x) || py::isinstance<py::bytes>(x) || py::hasattr(x, "__fspath__");
}

py::object optional_number(const std::optional<double>& x) { return x ? py::object(py::float_(*x)) : py::none(); }

// The scores as the CLI's JSON names them (None where undefined).
py::dict scores_dict(const meshsal::EvalScores& s) {
  py::dict d;
  d["cc"] = optional_number(s.cc);
  d["auc_20"] = optional_number(s.auc_20);
  d["auc_5"] = optional_number(s.auc_5);
  d["nss"] = optional_number(s.nss);
  d["kld"] = optional_number(s.kld);
  d["sim"] = optional_number(s.sim);
  d["vertices"] = s.vertices;
  d["positives_20"] = s.positives_20;
  d["positives_5"] = s.positives_5;
  d["threshold_20"] = s.threshold_20;
  d["threshold_5"] = s.threshold_5;
  d["nss_vertices"] = s.nss_vertices;
  d["notes"] = py::cast(s.notes);
  return d;
}

py::dict evaluate(const py::object& pred, const py::object& gt, const std::string& attribute,
                  const std::string& gt_attribute, const py::object& gt_column, const std::string& transfer,
                  const py::object& smooth, const py::object& threads, const py::object& max_input_bytes) {
  if (transfer != "none" && transfer != "nearest")
    throw py::value_error("transfer must be 'none' or 'nearest', got '" + transfer + "'");
  const bool pred_path = path_like(pred), gt_path = path_like(gt);
  if (!pred_path && !gt_path) {
    // Two arrays of values: the scores alone.
    if (attribute != "quality" || gt_attribute != "quality" || transfer != "none" ||
        integer_arg(gt_column, "gt_column", 0, 1000000) != 0 || number_arg(smooth, "smooth") != 0)
      throw py::value_error("attribute, gt_attribute, gt_column, transfer and smooth apply to files; "
                            "pred and gt here are arrays of values");
    const size_t n = size_t(py::len(pred));
    const std::vector<double> p = vertex_values(pred, n, "pred");
    const std::vector<double> g = vertex_values(gt, n, "gt");
    meshsal::EvalScores s;
    {
      py::gil_scoped_release release;
      s = meshsal::evaluate_scores(p, g);
    }
    return scores_dict(s);
  }
  if (!pred_path || !gt_path)
    throw py::type_error("pred and gt must both be paths (str, bytes, os.PathLike) or both arrays of values");
  meshsal::EvalOptions o;
  o.attribute = attribute;
  o.gt_attribute = gt_attribute;
  o.gt_column = int(integer_arg(gt_column, "gt_column", 0, 1000000));
  o.transfer = transfer == "nearest" ? meshsal::EvalTransfer::Nearest : meshsal::EvalTransfer::None;
  o.smooth = number_arg(smooth, "smooth");
  o.threads = count_arg(threads, "threads");
  o.max_input_bytes = unsigned_arg(max_input_bytes, "max_input_bytes", 0, UINT64_MAX);
  const std::string pred_file = path_bytes(pred), gt_file = path_bytes(gt);
  meshsal::EvalReport r;
  try {
    py::gil_scoped_release release;
    r = meshsal::evaluate_files(pred_file, gt_file, o);
  } catch (const meshsal::Error& e) {
    const std::string m = e.what();
    raise_file_error(e, m.compare(0, gt_file.size() + 1, gt_file + ":") == 0 ? gt : pred);
  }
  // The keys of `meshsal eval --json` (but seconds and device).
  py::dict d;
  d["mesh"] = pred_file;
  d["pred"] = pred_file;
  d["gt"] = gt_file;
  d["attribute"] = attribute;
  d["gt_source"] = r.gt_is_text ? "text" : "mesh";
  if (r.gt_is_text) {
    d["gt_column"] = r.gt_column;
  } else {
    d["gt_attribute"] = gt_attribute;
    d["gt_vertices"] = r.gt_vertices;
  }
  d["vertices"] = r.vertices;
  d["scored_vertices"] = r.raw.vertices;
  d["vertices_without_gt"] = r.vertices_without_gt;
  if (r.gt_is_text) {
    d["gt_rows"] = r.gt_rows;
    d["matched_rows"] = r.matched_rows;
    d["unmatched_rows"] = r.unmatched_rows;
    d["unmatched_lines"] = py::cast(r.unmatched_lines);
  }
  d["transfer"] = r.transferred ? "nearest" : "none";
  d["diagonal"] = r.diagonal;
  if (r.transferred) {
    d["transfer_max_distance"] = r.transfer_max_distance;
    d["transfer_max_distance_percent"] = r.diagonal > 0 ? 100 * r.transfer_max_distance / r.diagonal : 0.0;
    d["transfer_mean_distance"] = r.transfer_mean_distance;
    d["transfer_mean_distance_percent"] = r.diagonal > 0 ? 100 * r.transfer_mean_distance / r.diagonal : 0.0;
  }
  d["raw"] = scores_dict(r.raw);
  d["smooth"] = r.smoothed ? py::object(py::float_(o.smooth)) : py::none();
  if (r.smoothed) d["smooth_sigma"] = r.smooth_sigma;
  d["smoothed"] = r.smoothed ? py::object(scores_dict(*r.smoothed)) : py::none();
  std::vector<std::string> notes = r.notes;
  for (const std::string& n : r.raw.notes) notes.push_back(n);
  if (r.smoothed)
    for (const std::string& n : r.smoothed->notes) notes.push_back("smoothed: " + n);
  d["notes"] = py::cast(notes);
  return d;
}

}  // namespace

void bind_eval(py::module_& m) {
  m.def("evaluate", &evaluate, py::arg("pred"), py::arg("gt"), py::kw_only(), py::arg("attribute") = "quality",
        py::arg("gt_attribute") = "quality", py::arg("gt_column") = 0, py::arg("transfer") = "none",
        py::arg("smooth") = 0.0, py::arg("threads") = 0, py::arg("max_input_bytes") = 0ULL,
        R"(evaluate(pred, gt, *, attribute='quality', gt_attribute='quality', gt_column=0,
         transfer='none', smooth=0.0, threads=0, max_input_bytes=0) -> dict

Scores a per-vertex prediction against ground truth as `meshsal eval PRED GT` does (SPEC
section 7; every vertex once): CC, AUC-20%, AUC-5%, NSS, KLD and SIM. A score the data leave
undefined (CC or NSS of a constant, AUC without negatives, KLD of an all-zero map) is None,
with a line in 'notes' saying why.

Files (str, bytes or os.PathLike): PRED is a mesh whose per-vertex scalar `attribute` holds
the prediction (quality: PLY quality, glTF _SALIENCY); GT a mesh with PRED's vertices and a
scalar `gt_attribute`, or text rows `x y z ... value` (any name that is no mesh format)
with the value in the 1-based column `gt_column` (0: the last), joined to the vertex at the
same position (within 1e-6 of the diagonal; unmatched rows counted in 'unmatched_rows',
their lines in 'unmatched_lines'). transfer='nearest': each PRED vertex takes the value of
the nearest GT vertex or row (GT on another mesh). smooth=SIGMA (a fraction of the
bounding-box diagonal, at most 0.5) also scores PRED smoothed by the library's Gaussian
filter, under 'smoothed', beside 'raw'. Returns the dict of `meshsal eval --json` (without
'seconds' and 'device').

Arrays: evaluate(p, g) with two 1-D arrays of one value per vertex returns the scores
alone (the dict under 'raw' above).)");
}

}  // namespace meshsal_py
