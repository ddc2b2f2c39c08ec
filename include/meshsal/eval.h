// meshsal public interface: scoring a per-vertex prediction against ground truth (SPEC
// section 7; `meshsal eval`, Python's evaluate()).
// Part of meshsal.h (which includes every part); the conventions at the top of
// meshsal.h hold for every function here.
#pragma once
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "meshsal/mesh.h"

namespace meshsal {

// ------------------------------------------------------------------------------------------
// Evaluation against ground truth (SPEC section 7, docs/method.md "Evaluation")

// The eps of KLD (SPEC section 7).
constexpr double kEvalEps = 1e-12;

// The scores of a prediction p against ground truth g, one value each per vertex, every
// vertex counted once (not weighted by area). A score that the data leave undefined is
// nullopt (JSON null, Python None) and `notes` says why; none is ever NaN.
struct EvalScores {
  size_t vertices = 0;            // n, the values scored
  std::optional<double> cc;       // Pearson correlation; undefined when p or g is constant
  // AUC-q: positives are the vertices with g at or above the (1 - q) quantile of g, taken as
  // the value of 0-based rank n - ceil(q n) in ascending order (the ceil(q n)-th largest),
  // ties included; AUC = P(p of a positive > p of a negative) + P(equal) / 2 (Mann-Whitney,
  // from average ranks). Undefined when every vertex is a positive (no negative).
  std::optional<double> auc_20, auc_5;
  size_t positives_20 = 0, positives_5 = 0;
  double threshold_20 = 0, threshold_5 = 0;  // the quantiles of g
  // NSS: mean of (p - mean p) / std p (population std, divided by n) over the vertices with
  // g > 0 (nss_vertices of them). Undefined when p is constant or no g is above 0.
  std::optional<double> nss;
  size_t nss_vertices = 0;
  // p and g each shifted by their minimum when it is negative, then scaled to sum 1.
  // KLD = sum g_i log(eps + g_i / (eps + p_i)); SIM = sum min(p_i, g_i). Undefined when p or
  // g sums to 0 after the shift (all zero, or constant and shifted to zero).
  std::optional<double> kld, sim;
  std::vector<std::string> notes;  // one line per undefined score (or group of them)
};

// Scores p against g (same length). Throws Error when the lengths differ, there are fewer
// than 2 values, or a value is not finite ("prediction value 7 is nan").
EvalScores evaluate_scores(const std::vector<double>& p, const std::vector<double>& g);

// Ground truth as text: one row per point, `x y z ... value` (whitespace or commas between
// fields; empty lines and lines starting with # skipped; a first line that is not all
// numbers is a header, skipped).
struct VertexRows {
  std::vector<double> xyz;      // 3 per row, the model's coordinates
  std::vector<double> values;   // one per row
  std::vector<size_t> lines;    // each row's line number in the file (1-based)
  size_t columns = 0;           // fields per row (every row has the same number)
};

// Reads rows from `path` (optionally gzipped); `column` is the 1-based column holding the
// value (4 or more; 0 = the last). Throws Error naming the file and line for a row with
// fewer than 4 fields, another field count than the first row's, a field that is not a
// number, a non-finite coordinate or value, or a column beyond the row; and for a file
// with no row. max_input_bytes: as LoadOptions's (0: 1 GiB).
VertexRows read_vertex_rows(const std::string& path, int column = 0, uint64_t max_input_bytes = 0);

// The same from text in memory (`name` starts the messages).
VertexRows parse_vertex_rows(const std::string& text, const std::string& name, int column = 0);

// Rows joined to the vertices of a mesh at their positions (SPEC section 7): a row goes to
// every vertex within 1e-6 of the bounding-box diagonal of the mesh points (in the model's
// coordinates; several when vertices share a position: duplicates, seam twins). A row
// within reach of no vertex is unmatched: counted and listed, never guessed. Two rows
// reaching one vertex with different values are an Error naming both lines and the vertex.
struct JoinedRows {
  std::vector<double> values;     // per vertex (0 where has_value is 0)
  std::vector<uint8_t> has_value; // per vertex: 1 when a row reached it
  size_t rows = 0, matched_rows = 0, unmatched_rows = 0;
  std::vector<size_t> unmatched_lines;  // the first 20 unmatched rows' line numbers
  size_t vertices_without_value = 0;
};
JoinedRows join_vertex_rows(const Mesh& mesh, const VertexRows& rows);

// Ground truth carried to another mesh's vertices (`--transfer nearest`): each vertex of
// `target` takes the value of the nearest source point (model coordinates, 3 per point;
// ties: the lowest point index), found over the triangle BVH of core/surface_distance
// with each point a degenerate triangle. Also the largest and mean distance moved.
struct NearestValues {
  std::vector<double> values;  // per vertex of target
  double max_distance = 0, mean_distance = 0;
};
NearestValues transfer_nearest(const std::vector<double>& source_xyz, const std::vector<double>& source_values,
                               const Mesh& target);

// p smoothed by the library's Gaussian filter (the exact sweep of saliency and of
// smooth_saliency, SPEC section 1): over the mesh points within 2 sigma, sigma =
// sigma_frac x the bounding-box diagonal of the mesh points. Vertices no triangle uses keep
// their value. sigma_frac in (0, 0.5].
std::vector<double> smooth_vertex_values(const Mesh& mesh, const std::vector<double>& values, double sigma_frac,
                                         unsigned threads = 0);

enum class EvalTransfer { None, Nearest };

// What `meshsal eval PRED GT` and Python's evaluate(pred, gt) do with two files.
struct EvalOptions {
  std::string attribute = "quality";     // PRED's per-vertex scalar (glTF _SALIENCY is quality)
  std::string gt_attribute = "quality";  // GT's, when GT is a mesh
  int gt_column = 0;                     // GT as text rows: the value's 1-based column; 0 = last
  EvalTransfer transfer = EvalTransfer::None;
  double smooth = 0;                     // sigma_frac of smooth_vertex_values; 0 = no smoothing
  unsigned threads = 0;
  uint64_t max_input_bytes = 0;          // LoadOptions::max_input_bytes of both files
};

struct EvalReport {
  EvalScores raw;                      // p as read
  std::optional<EvalScores> smoothed;  // p smoothed (options.smooth), beside the raw scores
  double smooth_sigma = 0;             // the smoothing's sigma in model units (0: none)
  size_t vertices = 0;                 // PRED's vertices (every one scored that has g)
  bool gt_is_text = false;
  size_t gt_vertices = 0;              // GT mesh's vertices (text: 0)
  int gt_column = 0;                   // text: the column read (1-based)
  size_t gt_rows = 0, matched_rows = 0, unmatched_rows = 0;  // text without transfer
  std::vector<size_t> unmatched_lines;
  size_t vertices_without_gt = 0;      // PRED vertices no row reached: not scored
  bool transferred = false;
  double transfer_max_distance = 0, transfer_mean_distance = 0;  // model units
  double diagonal = 0;                 // PRED's mesh points' bounding-box diagonal
  std::vector<std::string> notes;      // what a user should know (unmatched rows, ...)
};

// Loads PRED (its scalar attribute options.attribute) and GT (a mesh's gt_attribute, or
// text rows when GT's name is no mesh format) and scores them. A GT mesh must have PRED's
// vertices (count and positions within 1e-6 of the diagonal) unless options.transfer says
// Nearest; text rows are joined by position (join_vertex_rows) unless Nearest, which
// carries them as points. Errors name the file, vertex or line: a missing attribute (with
// the ones the file has), a non-finite value, mismatched vertices (suggesting --transfer
// nearest), fewer than 2 vertices with ground truth.
EvalReport evaluate_files(const std::string& pred, const std::string& gt, const EvalOptions& options = {});

}  // namespace meshsal
