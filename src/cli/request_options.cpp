#include "request_options.h"

#include <cstdio>

#include "command.h"
#include "interrupt.h"
#include "load_input.h"
#include "mpi_world.h"
#include "json_string.h"
#include "number_options.h"
#include "progress.h"
#include "saliency/saliency.h"
#include "saliency_output.h"

namespace meshsal::cli {

namespace {

// --up, once per command (the saliency and view groups both take it).
CLI::Option* add_up_option(CLI::App& app, RequestText& t) {
  if (CLI::Option* given = app.get_option_no_throw("--up")) return given;
  return app.add_option("--up", t.up,
                        "the model's up axis (pictures, the view's angles, and the views and height of --model "
                        "perceptual): x, y, z, -x, -y or -z")
      ->capture_default_str()->check(CLI::IsMember({"x", "y", "z", "-x", "-y", "-z"}));
}

}  // namespace

void add_saliency_options(CLI::App& app, RequestText& t) {
  app.add_option("--model", t.model,
                 "What S models: lee2005 (the paper's geometric saliency), perceptual (a prediction of where "
                 "people look at the rendered object: exposure over views from 10-30 degrees above the horizon "
                 "around --up, with occlusion and centre bias, times 1 + height + rarity + coarse saliency, "
                 "smoothed to a fixation's size; docs/method.md), or one of its cues alone: exposure, centre, "
                 "height, rarity, coarse")
      ->capture_default_str()
      ->check(CLI::IsMember({"lee2005", "perceptual", "exposure", "centre", "center", "height", "rarity", "coarse"}));
  add_up_option(app, t);
  app.add_option("--backend", t.backend,
                 "auto (a GPU when present, else the CPU), gpu (any Vulkan device, lavapipe included) or cpu")
      ->capture_default_str();
  add_precision_option(app, &t.precision);
  add_method_option(app, &t.method);
  app.add_option("--device", t.device, "Vulkan device index for the gpu backend (see `meshsal devices`)")
      ->check(whole_in(-1, 255));
  app.add_option("--scales", t.scales,
                 "Center-surround scales in units of eps: scale k compares the Gaussian averages of curvature at "
                 "k*eps and 2k*eps")
      ->capture_default_str()->check(scales_list());
  app.add_option("--eps-frac", t.eps_frac, "eps as a fraction of the bounding-box diagonal")
      ->capture_default_str()->check(finite_in(0, meshsal::kMaxEpsFrac, true));
  add_threads_option(app, t.threads,
                     "CPU threads (0 = all cores; under mpirun the default is each machine's cores shared among "
                     "its ranks)")
      ->each([&t](const std::string&) { t.threads_given = true; });
}

CLI::Option* add_saliency_from_option(CLI::App& app, RequestText& t, const std::string& names) {
  return app.add_option(names, t.saliency_from,
                        "Read S from this file instead of computing it: a PLY (`quality`) or glTF (`_SALIENCY`) that "
                        "`meshsal saliency` wrote for this mesh");
}

std::vector<CLI::Option*> add_view_options(CLI::App& app, RequestText& t) {
  std::vector<CLI::Option*> out;
  out.push_back(add_up_option(app, t));
  out.push_back(add_elevation_option(app, &t.elevation));
  out.push_back(app.add_option("--restarts", t.restarts, "best view: gradient-ascent restarts from random directions")
                    ->capture_default_str()->check(whole_in(1, meshsal::kMaxViewRestarts)));
  out.push_back(app.add_option("--seed", t.seed, "best view: seed of the random starts")->capture_default_str());
  out.push_back(app.add_option("--resolution", t.resolution, "best view: z-buffer side in pixels")
                    ->capture_default_str()->check(whole_in(meshsal::kMinImageSize, meshsal::kMaxImageSize)));
  out.push_back(app.add_option("--depth-tol", t.depth_tol, "best view: visibility depth tolerance in pixel widths")
                    ->capture_default_str()->check(finite_in(0, meshsal::kMaxDepthTolPx)));
  out.push_back(app.add_option("--score", t.score, "colour and search by saliency, or curvature (|H|, the paper's baseline)")
                    ->capture_default_str()->check(CLI::IsMember({"saliency", "curvature"})));
  return out;
}

void add_picture_options(CLI::App& app, RequestText& t, const std::string& size_help) {
  app.add_option("--size", t.size, size_help)->capture_default_str()->check(whole_in(meshsal::kMinImageSize, meshsal::kMaxImageSize));
  add_color_range_option(app, t);
}

void add_color_range_option(CLI::App& app, RequestText& t) {
  app.add_option("--color-range", t.color_range,
                 "LO,HI ends of the colour scale, values or percentiles (e.g. 0,0.5 or 5%,99%); default minimum,maximum")
      ->check(color_range_check());
}

void add_weight_options(CLI::App& app, RequestText& t) {
  app.add_option("--weights", t.weights,
                 "balanced (the paper's curve with alpha at the 50th percentile and lambda 3: salient "
                 "detail at little cost elsewhere), saliency (the paper's recipe, lambda 100 above the "
                 "30th percentile: more salient detail, RMS and Hausdorff error up to ~3x plain's) or "
                 "none (plain quadric error)")
      ->capture_default_str();
  app.add_option("--lambda", t.lambda, "Amplification of the salient vertices "
                 "(default: the --weights preset's: 3 for balanced, 100 for saliency)")
      ->check(finite_in(0, 1e6))->each([&t](const std::string&) { t.lambda_given = true; });
  app.add_option("--alpha-percentile", t.alpha_percentile,
                 "Percentile of Sm above which vertices are amplified (default: the --weights preset's: 50 "
                 "for balanced, 30 for saliency)")
      ->check(finite_in(0, 100))->each([&t](const std::string&) { t.alpha_given = true; });
  app.add_option("--weight-floor", t.weight_floor,
                 "Not in the paper: raise W to at least this fraction of its mean W, so that no collapse is free\n"
                 "(flat regions have Sm = 0; 0 = the paper's literal rule, which can erase them)")
      ->capture_default_str()->check(finite_in(0, 100));
}

void add_memory_options(CLI::App& app, RequestText& t, const std::string& help) {
  app.add_option("--memory-limit", t.memory_limit, help + " " + std::string(kSizeSyntax))->check(memory_size());
  add_temp_dir_option(app, &t.temp_dir);
}

void add_output_flags(CLI::App& app, RequestText& t, const std::string& json_help) {
  app.add_flag("-q,--quiet", t.quiet, "Print nothing on success (no notes either)");
  app.add_flag("--json", t.json, json_help);
}

namespace {

// A library parser's refusal as a usage error naming the option ("--weights must be ...").
template <typename Parse>
auto as_option(Parse parse) -> decltype(parse()) {
  try {
    return parse();
  } catch (const meshsal::Error& e) {
    throw UsageError(std::string("--") + e.what());
  }
}

}  // namespace

meshsal::Request request_from(const RequestText& t, Progress* progress) {
  using namespace meshsal;
  Request r;
  // The input limits every command honours (MESHSAL_MAX_INPUT).
  r.load = load_options();
  SaliencyOptions& so = r.saliency;
  so.cancel = interrupt_flag();
  so.eps_frac = t.eps_frac;
  so.scales = parse_scales(t.scales);
  // Ranks on one machine share its cores unless told otherwise.
  so.threads = !t.threads_given && mpi_world().active ? mpi_default_threads() : t.threads;
  so.backend = parse_backend(t.backend);
  so.precision = as_option([&] { return meshsal::parse_precision(t.precision); });
  so.method = as_option([&] { return meshsal::parse_method(t.method); });
  so.device = t.device;
  so.model = as_option([&] { return meshsal::parse_model(t.model); });
  so.up = parse_up_axis(t.up);
  if (progress) so.progress = [progress](const char* stage, double f) { progress->update(stage, f); };
  so.notice = [quiet = t.quiet](const std::string& line) {
    if (!quiet) std::fprintf(stderr, "%s\n", printable(line).c_str());
  };
  r.saliency_from = t.saliency_from;
  r.score = as_option([&] { return parse_score(t.score); });
  ViewpointOptions& vo = r.viewpoint;
  vo.up = parse_up_axis(t.up);
  if (!t.elevation.empty()) vo.elevation = parse_elevation_range(t.elevation);
  vo.optimiser.restarts = t.restarts;
  vo.optimiser.seed = t.seed;
  vo.visibility.resolution = t.resolution;
  vo.visibility.depth_tol_px = t.depth_tol;
  vo.visibility.threads = so.threads;
  vo.backend = so.backend;
  vo.device = t.device;
  vo.optimiser.progress = so.progress;
  vo.notice = so.notice;
  vo.optimiser.cancel = so.cancel;
  r.style.size = t.size;
  r.style.up = vo.up;
  if (!t.color_range.empty()) r.style.range = parse_color_range(t.color_range);
  r.page.range = r.style.range;
  r.weighting = as_option([&] { return parse_weighting(t.weights); });
  r.weight_options = weight_preset(r.weighting);
  if (t.lambda_given) r.weight_options.lambda = t.lambda;
  if (t.alpha_given) r.weight_options.alpha_percentile = t.alpha_percentile;
  r.weight_options.floor = t.weight_floor;
  r.simplify.threads = so.threads;
  r.simplify.cancel = so.cancel;
  if (!t.memory_limit.empty()) r.out_of_core.memory_limit = parse_memory_size(t.memory_limit);
  r.out_of_core.temp_dir = t.temp_dir;
  return r;
}

}  // namespace meshsal::cli
