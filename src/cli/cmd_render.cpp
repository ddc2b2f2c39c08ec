// `meshsal render`: a picture of the mesh coloured by saliency from any view (or the best
// one), titled and with its colour bar, or side by side with simplified versions of it.
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "command.h"
#include "json_string.h"
#include "core/timer.h"
#include "json_object.h"
#include "load_input.h"
#include "meshsal/meshsal.h"
#include "view/compare_picture.h"
#include "view/picture.h"
#include "view/render.h"
#include "api/viewpoint_score.h"
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
  std::string input, saliency_from, score = "saliency", output, backend = "auto", up = "y", color_range;
  std::string elevation;  // --elevation MIN,MAX with --best (empty: the whole sphere)
  // --best's search, as viewpoint's options and defaults
  int restarts = 8, resolution = meshsal::kDefaultViewResolution;
  uint64_t seed = 1;
  double depth_tol = 2.0;
  std::vector<std::string> compare;
  double theta_deg = 0, phi_deg = 0;
  int size = 512;
  bool grey = false, flat = false, edges = false, best = false, json = false, quiet = false;
  unsigned threads = 0;
};

int run(const Options& o) {
  using namespace meshsal;
  const meshsal::Timer t0;
  // Before any work: the picture is a writable .png that is none of the inputs.
  std::vector<std::string> inputs{o.input, o.saliency_from};
  inputs.insert(inputs.end(), o.compare.begin(), o.compare.end());
  check_outputs({{o.output, "-o", {".png"}}}, inputs);
  const Backend backend = parse_backend(o.backend);  // a usage error even where unused (--grey)
  RenderStyle style;
  style.size = o.size;
  style.smooth = !o.flat && o.compare.empty();
  style.edges = o.edges;
  style.up = parse_up_axis(o.up);
  if (!o.color_range.empty()) style.range = parse_color_range(o.color_range);
  check_render_style(style);
  if (!o.compare.empty() && o.compare.size() != 2)
    throw Error("--compare takes two meshes: PLAIN SALIENT");
  const double rad = 3.14159265358979323846 / 180.0;
  ViewAngles view{o.theta_deg * rad, o.phi_deg * rad};

  VertexProperties props;
  Mesh mesh = load_input(o.input, o.quiet, &props);
  const ViewScore kind = parse_view_score(o.score);
  std::vector<double> score;
  std::string source, device = "cpu";  // where the view was scored: the CPU unless --best ran on a GPU
  if (!o.grey || o.best) {
    Progress progress(!o.quiet && stderr_is_terminal());
    SaliencyOptions sopt;
    sopt.cancel = interrupt_flag();
    sopt.threads = o.threads;
    sopt.backend = backend;
    sopt.precision = meshsal::parse_precision(o.precision);
    sopt.method = meshsal::parse_method(o.method);
    sopt.progress = [&](const char* stage, double f) { progress.update(stage, f); };
    sopt.notice = [&o](const std::string& m) {
      if (!o.quiet) std::fprintf(stderr, "%s\n", printable(m).c_str());
    };
    const std::string from = saliency_source_file(o.input, props, o.saliency_from, kind == ViewScore::Saliency);
    score = vertex_score(mesh, kind, from, sopt, &source);
    progress.finish();
  }
  if (o.best) {
    // The view of most visible score: the one view pipeline (best_viewpoint), with the settings
    // `meshsal viewpoint` has by default, so both give the same view.
    ViewpointOptions vo;
    vo.up = style.up;
    if (!o.elevation.empty()) vo.elevation = parse_elevation_range(o.elevation);
    vo.restarts = o.restarts;
    vo.seed = o.seed;
    vo.resolution = o.resolution;
    vo.depth_tol_px = o.depth_tol;
    vo.threads = o.threads;
    vo.backend = parse_backend(o.backend);
    vo.notice = [](const std::string& m) { std::fprintf(stderr, "%s\n", printable(m).c_str()); };
    vo.cancel = interrupt_flag();
    const Viewpoint b = best_viewpoint(mesh, score, vo);
    view = b.view;
    device = b.backend_name;
    if (!o.quiet) std::fprintf(stderr, "best view: %s\n", view_text(view, style.up).c_str());
    if (!b.note.empty() && !o.quiet) std::fprintf(stderr, "note: %s\n", b.note.c_str());
  }
  const std::vector<double>* shown = o.grey ? nullptr : &score;
  const std::string name = std::filesystem::path(o.input).filename().string();
  const std::string score_name = kind == ViewScore::Saliency ? "saliency" : "|mean curvature|";
  VisibleScore visible;
  int width = 0, height = 0;  // of the picture written
  if (o.compare.empty()) {
    const Image picture = titled_view(mesh, shown, view, style, name, score_name, &visible);
    write_png(o.output, picture);
    width = picture.width, height = picture.height;
  } else {
    Mesh plain = load_input(o.compare[0], o.quiet);
    Mesh salient = load_input(o.compare[1], o.quiet);
    // Each panel is labelled with its file's name.
    const Image picture = compare_picture(mesh, shown, plain, salient, view, style, name,
                                          std::filesystem::path(o.compare[0]).filename().string(),
                                          std::filesystem::path(o.compare[1]).filename().string());
    write_png(o.output, picture);
    width = picture.width, height = picture.height;
    if (shown && o.json) visible = picture_visible_score(mesh, score, view, style.up);
  }
  if (!o.json) {
    // One line, as the other commands say what they wrote (stdout; --json replaces it).
    if (!o.quiet) std::printf("wrote %s (%dx%d)\n", printable(o.output).c_str(), width, height);
    return 0;
  }
  // The view in the angles of --up; visible_score = U of the original as the title gives it
  // (CPU visibility at 512 px), null without a score (--grey).
  JsonObject j;
  j.text("mesh", o.input).text("output", o.output).count("vertices", mesh.vertex_count())
      .count("faces", mesh.triangle_count()).text("device", device).text("up", o.up).flag("best", o.best);
  add_view(j, frame_mesh(mesh, style.up), view);
  if (shown)
    j.text("score", o.score).text("score_source", source).number("visible_score", visible.U)
        .number("visible_fraction", visible.total > 0 ? visible.U / visible.total : 0.0);
  else
    j.null("score").null("score_source").null("visible_score").null("visible_fraction");
  if (!o.compare.empty()) j.text("plain", o.compare[0]).text("salient", o.compare[1]);
  j.number("seconds", t0.seconds()).print();
  return 0;
}

RunFn setup(CLI::App& app) {
  auto o = std::make_shared<Options>();
  app.add_option("IN", o->input, "mesh (OBJ, PLY, OFF, STL, glTF, GLB, optionally .gz); a saliency PLY brings its own saliency")->required();
  app.add_option("-o,--output", o->output, "PNG to write")->required();
  auto* theta = app.add_option("--theta", o->theta_deg, "view longitude in degrees (0 looks from the front, 90 from the right)")
      ->capture_default_str()->check(finite_in(-360, 360));
  auto* phi = app.add_option("--phi", o->phi_deg, "view latitude in degrees (90 looks from above)")
      ->capture_default_str()->check(finite_in(-90, 90));
  auto* best = app.add_flag("--best", o->best, "render the view of most visible saliency (as `meshsal viewpoint` finds it)")
      ->excludes(theta)->excludes(phi);
  add_elevation_option(app, &o->elevation)->needs(best);
  app.add_option("--restarts", o->restarts, "--best: gradient-ascent restarts from random directions")
      ->capture_default_str()->check(whole_in(1, 1000))->needs(best);
  app.add_option("--seed", o->seed, "--best: seed of the random starts")->capture_default_str()->needs(best);
  app.add_option("--resolution", o->resolution, "--best: z-buffer side in pixels")
      ->capture_default_str()->check(whole_in(16, 8192))->needs(best);
  app.add_option("--depth-tol", o->depth_tol, "--best: visibility depth tolerance in pixel widths")
      ->capture_default_str()->check(finite_in(0, 1000))->needs(best);
  app.add_option("--up", o->up, "mesh axis that points up: x, y, z, -x, -y or -z (scans are often z up)")
      ->capture_default_str()->check(CLI::IsMember({"x", "y", "z", "-x", "-y", "-z"}));
  app.add_option("--color-range", o->color_range,
                 "LO,HI ends of the colour scale, values or percentiles (e.g. 0,0.5 or 5%,99%); default minimum,maximum")
      ->check(color_range_check());
  app.add_option("--saliency-from", o->saliency_from, "PLY with per-vertex 'quality' instead of computing saliency");
  app.add_option("--score", o->score, "colour by saliency or curvature (|H|)")
      ->capture_default_str()->check(CLI::IsMember({"saliency", "curvature"}));  // a usage error (2)
  app.add_option("--compare", o->compare,
                 "PLAIN SALIENT: two simplified meshes drawn right of IN, same camera, coloured by distance to IN")
      ->expected(2);
  app.add_option("--size", o->size, "image side in pixels (per panel)")->capture_default_str()->check(whole_in(16, 8192));
  app.add_flag("--grey", o->grey, "no saliency colours");
  app.add_flag("--flat", o->flat, "flat shading (always on with --compare, shows the triangles)");
  app.add_flag("--edges", o->edges, "darken triangle edges");
  app.add_option("--backend", o->backend, "saliency backend: auto, gpu or cpu")->capture_default_str();
  add_precision_option(app, &o->precision);
  add_method_option(app, &o->method);
  add_threads_option(app, o->threads, "CPU threads, 0 = all cores");
  app.add_flag("-q,--quiet", o->quiet, "Print nothing on success (no notes either)");
  app.add_flag("--json", o->json,
               "Print one JSON object on stdout: mesh, output, device, the view's angles (theta, phi, "
               "theta_deg, phi_deg, direction), visible_score U and visible_fraction, seconds");
  return [o]() { return run(*o); };
}

bool registered = register_command({"render", "PNG picture of a mesh coloured by saliency, or a side-by-side comparison", 70, setup});

}  // namespace
}  // namespace meshsal_cli
