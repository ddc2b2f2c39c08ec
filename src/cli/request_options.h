// meshsal CLI: the options every command that runs a request shares, each with one
// spelling, one help text and one default (meshsal::Request's), added by the groups below
// and turned into the Request by the library's parsers (parse_method, parse_scales, ...).
// A command adds the groups it takes, parses, builds its request, calls
// meshsal::run_request and prints what came back.
#pragma once
#include <cstdint>
#include <string>

#include <CLI/CLI.hpp>

#include "meshsal/meshsal.h"

namespace meshsal::cli {

struct RequestText {
  // S (add_saliency_options)
  std::string backend = "auto", precision = "auto", method = "exact", scales = "2,3,4,5,6", model = "lee2005";
  double eps_frac = 0.003;
  int device = -1;
  unsigned threads = 0;
  bool threads_given = false;  // --threads on the command line (else, under mpirun: mpi_default_threads)
  std::string saliency_from;  // add_saliency_from_option
  // The views (add_view_options) and pictures (add_picture_options)
  std::string up = "y", elevation, score = "saliency", color_range;
  int restarts = 8, resolution = meshsal::kDefaultViewResolution, size = 512;
  uint64_t seed = 1;
  double depth_tol = 2.0;
  // The weights of simplification (add_weight_options)
  std::string weights = meshsal::weighting_name(meshsal::kDefaultWeighting);
  double lambda = 100, alpha_percentile = 30, weight_floor = meshsal::kDefaultWeightFloor;
  bool lambda_given = false, alpha_given = false;
  // Out of core (add_memory_options)
  std::string memory_limit, temp_dir;
  // Every command (add_output_flags)
  bool quiet = false, json = false;
};

// --model --up --backend --precision --method --device --scales --eps-frac --threads (--up once:
// add_view_options takes it too).
void add_saliency_options(CLI::App& app, RequestText& t);
// --saliency-from FILE (a PLY or glTF that keeps S); `names` may add an older spelling.
CLI::Option* add_saliency_from_option(CLI::App& app, RequestText& t, const std::string& names = "--saliency-from");
// --up --elevation --restarts --seed --resolution --depth-tol --score; returned in the order
// given so that a command can make them need another option (render: --best).
std::vector<CLI::Option*> add_view_options(CLI::App& app, RequestText& t);
// --size --color-range.
void add_picture_options(CLI::App& app, RequestText& t, const std::string& size_help = "image side in pixels");
// --color-range alone (the page: drawn at the window's size).
void add_color_range_option(CLI::App& app, RequestText& t);
// --weights --lambda --alpha-percentile --weight-floor.
void add_weight_options(CLI::App& app, RequestText& t);
// --memory-limit --temp-dir.
void add_memory_options(CLI::App& app, RequestText& t, const std::string& help);
// -q --json.
void add_output_flags(CLI::App& app, RequestText& t, const std::string& json_help);

// The request the shared options make (input and outputs are the command's), with progress
// on `progress` (may be null), notices (and the run's notes) on stderr unless quiet, and
// Ctrl-C cancelling it.
// Throws UsageError for a name no parser takes.
class Progress;
meshsal::Request request_from(const RequestText& t, Progress* progress);

}  // namespace meshsal::cli
