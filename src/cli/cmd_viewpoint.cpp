// `meshsal viewpoint`: the view direction that sees the most saliency (SPEC 3), as JSON.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>

#include "command.h"
#include "json_string.h"
#include "core/timer.h"
#include "meshsal/meshsal.h"
#include "view/legend.h"
#include "view/map_picture.h"
#include "view/picture.h"
#include "view/camera.h"
#include "view/render.h"
#include "api/viewpoint_score.h"
#include "json_object.h"
#include "load_input.h"
#include "number_options.h"
#include "output_check.h"
#include "own_saliency.h"
#include "progress.h"
#include "saliency_output.h"
#include "view_json.h"
#include "interrupt.h"

namespace meshsal_cli {
namespace {

struct Options {
  std::string precision = "auto";  // --precision
  std::string method = "exact";    // --method
  std::string input, saliency_from, score = "saliency", backend = "auto", out_png, map_png, up = "y", color_range;
  std::string elevation;  // --elevation MIN,MAX (empty: the whole sphere)
  int restarts = 8, views = 0, resolution = meshsal::kDefaultViewResolution, size = 512, map_width = 720, device = -1;
  uint64_t seed = 1;
  double depth_tol = 2.0;
  unsigned threads = 0;
  bool json = false;  // accepted like every command's --json; the summary is always JSON
};

int run(const Options& o) {
  using namespace meshsal;
  const meshsal::Timer t0;
  // Before any work: the pictures are writable .png files, distinct, none of them an input.
  check_outputs({{o.out_png, "-o", {".png"}}, {o.map_png, "--map", {".png"}}}, {o.input, o.saliency_from});
  RenderStyle style;
  style.size = o.size;
  style.up = parse_up_axis(o.up);
  if (!o.color_range.empty()) style.range = parse_color_range(o.color_range);
  if (!o.out_png.empty()) check_render_style(style);
  Backend backend = parse_backend(o.backend);
  ViewScore kind = parse_view_score(o.score);
  VertexProperties props;
  Mesh mesh = load_input(o.input, false, &props);

  Progress progress(stderr_is_terminal());
  SaliencyOptions sopt;
  sopt.cancel = interrupt_flag();
  sopt.threads = o.threads;
  sopt.backend = backend;
  sopt.precision = parse_precision(o.precision);
  sopt.method = meshsal::parse_method(o.method);
  sopt.device = o.device;
  sopt.progress = [&](const char* stage, double f) { progress.update(stage, f); };
  sopt.notice = [](const std::string& m) { std::fprintf(stderr, "%s\n", printable(m).c_str()); };
  std::string source;
  std::vector<double> score = vertex_score(
      mesh, kind, saliency_source_file(o.input, props, o.saliency_from, kind == ViewScore::Saliency), sopt, &source);
  progress.finish();

  // The one view pipeline (best_viewpoint): searched in the frame of --up, angles in it.
  const int map_views = o.views > 0 ? o.views : (o.map_png.empty() ? 0 : 2000);
  ViewpointOptions vo;
  vo.up = style.up;
  vo.resolution = o.resolution;
  vo.depth_tol_px = o.depth_tol;
  if (!o.elevation.empty()) vo.elevation = parse_elevation_range(o.elevation);
  vo.restarts = o.restarts;
  vo.seed = o.seed;
  vo.views = map_views;
  vo.threads = o.threads;
  vo.backend = backend;
  vo.device = o.device;
  // The optimiser reports after every batch of views ("best view"), then the map ("view map").
  vo.progress = [&](const char* stage, double f) { progress.update(stage, f); };
  vo.notice = sopt.notice;
  vo.cancel = interrupt_flag();
  const Viewpoint v = best_viewpoint(mesh, score, vo);
  progress.finish();
  const OptimiserResult& best = v.optimised;
  const ViewMap& map = v.map;
  const ViewAngles best_view = v.view;
  const ViewFrame up_frame = frame_mesh(mesh, style.up);

  const std::string name = std::filesystem::path(o.input).filename().string();
  const std::string score_name = kind == ViewScore::Saliency ? "saliency" : "|mean curvature|";
  if (!o.out_png.empty())
    write_png(o.out_png, titled_view(mesh, &score, best_view, style, name, score_name));
  if (!o.map_png.empty()) {
    char ring[96], cross[96];
    std::snprintf(ring, sizeof ring, "exhaustive maximum (%d views), U = %s", map_views,
                  value_text(map.U[map.best]).c_str());
    std::snprintf(cross, sizeof cross, "optimiser's result, U = %s", value_text(best.U).c_str());
    write_png(o.map_png, view_map_picture(map, o.map_width, map.views[map.best], ring, best_view, cross,
                                          name + ": visible " + score_name + " by view direction (--up " + o.up + ")"));
  }

  // One JSON object, as every command's --json: the best view's angles in the frame of --up,
  // visible_score = U (sum of the score over the visible mesh points), visible_fraction = U
  // over the sum over all points.
  JsonObject j;
  j.text("mesh", o.input).count("vertices", mesh.vertex_count()).count("faces", mesh.triangle_count())
      .text("score", o.score).text("score_source", source).text("device", v.backend_name)
      .count("resolution", uint64_t(o.resolution)).number("depth_tol_px", o.depth_tol).text("up", o.up);
  if (!o.elevation.empty()) j.numbers("elevation", {vo.elevation.min, vo.elevation.max});
  add_view(j, up_frame, best_view).number("visible_score", v.U).number("visible_fraction", v.visible_fraction);
  j.count("restarts", uint64_t(o.restarts)).count("seed", o.seed);
  if (!v.note.empty()) {
    j.text("note", v.note);
    std::fprintf(stderr, "note: %s\n", v.note.c_str());
  }
  if (map_views > 0) {
    JsonObject ex;
    ex.count("views", uint64_t(map_views));
    add_view(ex, up_frame, map.views[map.best]).number("visible_score", map.U[map.best])
        .number("visible_fraction", v.total > 0 ? map.U[map.best] / v.total : 0.0);
    j.object("exhaustive", ex);
  } else {
    j.null("exhaustive");
  }
  j.count("views_evaluated", best.views_evaluated + uint64_t(map_views));
  if (!o.out_png.empty()) j.text("output", o.out_png);
  if (!o.map_png.empty()) j.text("map", o.map_png);
  j.number("seconds", t0.seconds()).print();
  return 0;
}

RunFn setup(CLI::App& app) {
  auto o = std::make_shared<Options>();
  app.footer(
      "Print one JSON object: the direction that sees the most score (theta, phi in radians and\n"
      "degrees in the frame of --up, and `direction`, a unit vector towards the viewer),\n"
      "visible_score = U, the sum of the score over the mesh points visible from it, and\n"
      "visible_fraction = U over the sum over all points; `exhaustive`: the best of --views\n"
      "directions (null without --views or --map).");
  app.add_option("IN", o->input, "mesh (OBJ, PLY, OFF, STL, glTF, GLB, optionally .gz); a saliency PLY brings its own saliency")->required();
  app.add_option("--saliency-from", o->saliency_from, "PLY with per-vertex 'quality' (from `meshsal saliency`) instead of computing it");
  app.add_option("--score", o->score, "saliency, or curvature (|H|, the paper's baseline)")
      ->capture_default_str()->check(CLI::IsMember({"saliency", "curvature"}));  // a usage error (2)
  app.add_option("--restarts", o->restarts, "gradient-ascent restarts from random directions")
      ->capture_default_str()->check(whole_in(1, 1000));
  app.add_option("--seed", o->seed, "seed of the random starts")->capture_default_str();
  app.add_option("--views", o->views, "also evaluate N Fibonacci-sphere directions exhaustively (0: only with --map, 2000)")
      ->capture_default_str()->check(whole_in(0, 1000000));
  app.add_option("--resolution", o->resolution, "z-buffer side in pixels")->capture_default_str()->check(whole_in(16, 8192));
  add_elevation_option(app, &o->elevation);
  app.add_option("--depth-tol", o->depth_tol, "visibility depth tolerance in pixel widths")
      ->capture_default_str()->check(finite_in(0, 1000));
  app.add_option("--backend", o->backend, "visibility (and saliency) backend: auto, gpu or cpu")->capture_default_str();
  add_precision_option(app, &o->precision);
  add_method_option(app, &o->method);
  app.add_option("--device", o->device, "Vulkan device index (see `meshsal devices`)")->check(whole_in(-1, 255));
  add_threads_option(app, o->threads, "CPU threads, 0 = all cores");
  app.add_option("-o,--output", o->out_png, "PNG of the mesh coloured by score from the best view");
  app.add_option("--map", o->map_png, "PNG of U over all directions (equirectangular)");
  app.add_option("--size", o->size, "side of the -o picture in pixels")->capture_default_str()->check(whole_in(16, 8192));
  app.add_option("--up", o->up, "mesh axis that points up (pictures and the angles printed): x, y, z, -x, -y or -z")
      ->capture_default_str()->check(CLI::IsMember({"x", "y", "z", "-x", "-y", "-z"}));
  app.add_option("--color-range", o->color_range,
                 "LO,HI ends of the -o picture's colour scale, values or percentiles (e.g. 5%,99%); default minimum,maximum")
      ->check(color_range_check());
  app.add_option("--map-width", o->map_width, "width of the --map picture in pixels")
      ->capture_default_str()->check(whole_in(32, 8192));
  app.add_flag("--json", o->json,
               "Print the result as one JSON object on stdout (always so; accepted like the other commands' --json)");
  return [o]() { return run(*o); };
}

bool registered = register_command({"viewpoint", "best view direction by visible saliency (JSON), pictures", 60, setup});

}  // namespace
}  // namespace meshsal_cli
