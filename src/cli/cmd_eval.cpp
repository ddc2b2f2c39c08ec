// meshsal eval PRED GT: a per-vertex prediction scored against ground truth (SPEC section 7),
// by the library's evaluate_files; this file only parses and prints.
#include <cstdio>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "command.h"
#include "core/timer.h"
#include "json_object.h"
#include "load_input.h"
#include "meshsal/meshsal.h"
#include "number_options.h"
#include "request_options.h"

namespace meshsal::cli {
namespace {

struct Args {
  std::string pred, gt;
  std::string attribute = "quality", gt_attribute = "quality", transfer = "none";
  int gt_column = 0;
  double smooth = 0;
  RequestText text;  // --threads, --json, -q
};

void put(JsonObject& j, const std::string& key, const std::optional<double>& x) {
  if (x) j.number(key, *x);
  else j.null(key);
}

JsonObject scores_json(const EvalScores& s) {
  JsonObject j;
  put(j, "cc", s.cc);
  put(j, "auc_20", s.auc_20);
  put(j, "auc_5", s.auc_5);
  put(j, "nss", s.nss);
  put(j, "kld", s.kld);
  put(j, "sim", s.sim);
  j.count("vertices", s.vertices).count("positives_20", s.positives_20).count("positives_5", s.positives_5)
      .number("threshold_20", s.threshold_20).number("threshold_5", s.threshold_5)
      .count("nss_vertices", s.nss_vertices).strings("notes", s.notes);
  return j;
}

std::string cell(const std::optional<double>& x) {
  char buf[32];
  if (!x) return "undefined";
  std::snprintf(buf, sizeof buf, "%.6g", *x);
  return buf;
}

int run(const Args& a) {
  const meshsal::Timer t0;
  EvalOptions o;
  o.attribute = a.attribute;
  o.gt_attribute = a.gt_attribute;
  o.gt_column = a.gt_column;
  o.transfer = a.transfer == "nearest" ? EvalTransfer::Nearest : EvalTransfer::None;
  o.smooth = a.smooth;
  o.threads = a.text.threads;
  o.max_input_bytes = load_options().max_input_bytes;
  const EvalReport r = evaluate_files(a.pred, a.gt, o);

  std::vector<std::string> notes = r.notes;
  for (const std::string& n : r.raw.notes) notes.push_back(n);
  if (r.smoothed)
    for (const std::string& n : r.smoothed->notes) notes.push_back("smoothed: " + n);
  if (a.text.json) {
    JsonObject j;
    j.text("mesh", a.pred).text("pred", a.pred).text("gt", a.gt).text("attribute", a.attribute)
        .text("gt_source", r.gt_is_text ? "text" : "mesh");
    if (r.gt_is_text) j.count("gt_column", uint64_t(r.gt_column));
    else j.text("gt_attribute", a.gt_attribute).count("gt_vertices", r.gt_vertices);
    j.count("vertices", r.vertices).count("scored_vertices", r.raw.vertices)
        .count("vertices_without_gt", r.vertices_without_gt);
    if (r.gt_is_text) {
      std::vector<double> lines(r.unmatched_lines.begin(), r.unmatched_lines.end());
      j.count("gt_rows", r.gt_rows).count("matched_rows", r.matched_rows).count("unmatched_rows", r.unmatched_rows)
          .numbers("unmatched_lines", lines);
    }
    j.text("transfer", r.transferred ? "nearest" : "none").number("diagonal", r.diagonal);
    if (r.transferred)
      j.number("transfer_max_distance", r.transfer_max_distance)
          .number("transfer_max_distance_percent", r.diagonal > 0 ? 100 * r.transfer_max_distance / r.diagonal : 0)
          .number("transfer_mean_distance", r.transfer_mean_distance)
          .number("transfer_mean_distance_percent", r.diagonal > 0 ? 100 * r.transfer_mean_distance / r.diagonal : 0);
    j.object("raw", scores_json(r.raw));
    if (r.smoothed)
      j.number("smooth", a.smooth).number("smooth_sigma", r.smooth_sigma).object("smoothed", scores_json(*r.smoothed));
    else
      j.null("smooth").null("smoothed");
    j.strings("notes", notes).text("device", "cpu").number("seconds", t0.seconds());
    j.print();
  } else if (!a.text.quiet) {
    std::printf("eval       %s against %s: %zu of %zu vertices scored\n", a.pred.c_str(), a.gt.c_str(), r.raw.vertices,
                r.vertices);
    if (r.gt_is_text)
      std::printf("truth      text rows, column %d: %zu of %zu rows %s\n", r.gt_column, r.matched_rows, r.gt_rows,
                  r.transferred ? "carried (nearest)" : "matched a vertex");
    else
      std::printf("truth      '%s' of %zu vertices%s\n", a.gt_attribute.c_str(), r.gt_vertices,
                  r.transferred ? ", carried (nearest)" : "");
    if (r.transferred)
      std::printf("transfer   nearest point: max %.6g, mean %.6g (%.4g%% and %.4g%% of the diagonal)\n",
                  r.transfer_max_distance, r.transfer_mean_distance, 100 * r.transfer_max_distance / r.diagonal,
                  100 * r.transfer_mean_distance / r.diagonal);
    if (r.smoothed) std::printf("%-10s %-12s smoothed (sigma %g of the diagonal)\n", "score", "raw", a.smooth);
    else std::printf("%-10s %s\n", "score", "raw");
    const std::pair<const char*, std::optional<double> EvalScores::*> rows[] = {
        {"CC", &EvalScores::cc},   {"AUC-20%", &EvalScores::auc_20}, {"AUC-5%", &EvalScores::auc_5},
        {"NSS", &EvalScores::nss}, {"KLD", &EvalScores::kld},        {"SIM", &EvalScores::sim}};
    for (const auto& [name, member] : rows) {
      if (r.smoothed)
        std::printf("%-10s %-12s %s\n", name, cell(r.raw.*member).c_str(), cell((*r.smoothed).*member).c_str());
      else
        std::printf("%-10s %s\n", name, cell(r.raw.*member).c_str());
    }
    std::fflush(stdout);
  }
  // Notes on stderr (stdout holds only the table or the JSON, which has them too).
  if (!a.text.quiet)
    for (const std::string& n : notes) std::fprintf(stderr, "note: %s\n", n.c_str());
  return 0;
}

RunFn setup(CLI::App& sub) {
  auto a = std::make_shared<Args>();
  sub.footer(
      "Score a per-vertex prediction (PRED: a mesh whose scalar vertex attribute --attribute holds\n"
      "it, S by default: PLY quality, glTF _SALIENCY) against ground truth GT on the same\n"
      "vertices (SPEC section 7; docs/method.md, \"Evaluation\"), every vertex once, not by area:\n"
      "CC (Pearson), AUC-20% and AUC-5% (positives: GT at or above its 80th / 95th percentile,\n"
      "ties included; Mann-Whitney, ties half), NSS (over GT > 0), KLD and SIM (each shifted to\n"
      "non-negative and scaled to sum 1; eps 1e-12). GT is a mesh with the same vertices and a\n"
      "scalar --gt-attribute, or text rows `x y z ... value` (any name that is no mesh format:\n"
      ".txt, .csv, .xyz; spaces or commas; # comments; a header line) joined to the vertex at the\n"
      "same position (within 1e-6 of the diagonal); rows that match no vertex are counted and\n"
      "listed, never guessed, and vertices no row reaches are not scored. --transfer nearest\n"
      "gives each PRED vertex the value of the nearest GT vertex or row instead (GT on another\n"
      "mesh of the same object). --smooth SIGMA also scores PRED smoothed by a Gaussian of sigma\n"
      "SIGMA x the bounding-box diagonal, beside the raw scores. A score the data leave\n"
      "undefined (CC and NSS of a constant, AUC without negatives, KLD of an all-zero map) is\n"
      "`undefined` (JSON null) with a note saying why.");
  sub.add_option("pred", a->pred, "The prediction: a mesh file with a per-vertex scalar")->required();
  sub.add_option("gt", a->gt, "The ground truth: a mesh file, or text rows x y z ... value")->required();
  sub.add_option("--attribute", a->attribute, "PRED's per-vertex attribute (quality: PLY quality, glTF _SALIENCY)")
      ->capture_default_str();
  sub.add_option("--gt-attribute", a->gt_attribute, "GT's per-vertex attribute, when GT is a mesh")
      ->capture_default_str();
  sub.add_option("--gt-column", a->gt_column,
                 "Text GT: the 1-based column that holds the value (0 = the last column of the rows)")
      ->capture_default_str()->check(whole_in(0, 1000000));
  sub.add_option("--transfer", a->transfer,
                 "none: GT has PRED's vertices; nearest: each PRED vertex takes the nearest GT vertex's (or row's) value")
      ->capture_default_str()->check(CLI::IsMember({"none", "nearest"}));
  sub.add_option("--smooth", a->smooth,
                 "Also score PRED smoothed by a Gaussian of sigma SIGMA x the bounding-box diagonal (0: not)")
      ->capture_default_str()->check(finite_in(0, 0.5));
  add_threads_option(sub, a->text.threads, "CPU threads of --smooth (0 = all cores)");
  add_output_flags(sub, a->text, "Print the result as one JSON object on stdout; -q: no table and no notes");
  return [a] {
    if (a->gt_column != 0 && a->gt_column < 4)
      throw UsageError("--gt-column must be 4 or more (x y z come first), or 0 for the last column");
    return run(*a);
  };
}

const bool registered = register_command(
    {"eval", "Score a per-vertex prediction against ground truth (CC, AUC, NSS, KLD, SIM)", 30, setup});

}  // namespace
}  // namespace meshsal::cli
