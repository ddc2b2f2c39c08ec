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
#include "view/picture.h"
#include "view/camera.h"
#include "json_object.h"
#include "load_input.h"
#include "number_options.h"
#include "output_check.h"
#include "progress.h"
#include "request_options.h"
#include "saliency_output.h"
#include "view_json.h"
#include "interrupt.h"

namespace meshsal::cli {
namespace {

struct Options {
  std::string input, out_png, map_png;
  int views = 0, map_width = 720;
  RequestText text;  // the options every command shares
};

int run(Options o) {
  using namespace meshsal;
  Progress progress(!o.text.quiet && stderr_is_terminal());
  Request r = request_from(o.text, &progress);
  r.input = o.input;
  r.find_view = true;
  r.saliency_from_input = true;  // a saliency PLY or glTF brings its own S
  r.viewpoint.views = o.views;
  r.picture_output = o.out_png;
  r.map_output = o.map_png;
  r.map_width = o.map_width;
  const RequestResult result = run_request(r);
  progress.finish();
  const Viewpoint& v = result.viewpoint;
  const ViewFrame up_frame = frame_mesh(result.mesh, r.viewpoint.up);
  // One JSON object, as every command's --json: the best view's angles in the frame of --up,
  // visible_score = U (sum of the score over the visible mesh points), visible_fraction = U
  // over the sum over all points (-q: no notes or progress; the result is printed).
  const int map_views = int(v.map.views.size());
  JsonObject j;
  j.text("mesh", o.input).count("vertices", result.mesh.vertex_count()).count("faces", result.mesh.triangle_count())
      .text("score", o.text.score).text("score_source", result.saliency_source).text("device", v.backend_name)
      .count("resolution", uint64_t(o.text.resolution)).number("depth_tol_px", o.text.depth_tol).text("up", o.text.up);
  j.numbers("elevation", {r.viewpoint.elevation.min, r.viewpoint.elevation.max});  // the band searched, default or given
  add_view(j, up_frame, v.view).number("visible_score", v.U).number("visible_fraction", v.visible_fraction);
  j.count("restarts", uint64_t(o.text.restarts)).count("seed", o.text.seed);
  if (!v.note.empty()) j.text("note", v.note);
  if (map_views > 0) {
    JsonObject ex;
    ex.count("views", uint64_t(map_views));
    add_view(ex, up_frame, v.map.views[v.map.best]).number("visible_score", v.map.U[v.map.best])
        .number("visible_fraction", v.total > 0 ? v.map.U[v.map.best] / v.total : 0.0);
    j.object("exhaustive", ex);
  } else {
    j.null("exhaustive");
  }
  j.count("views_evaluated", v.optimised.views_evaluated + uint64_t(map_views));
  if (!o.out_png.empty()) j.text("output", o.out_png);
  if (!o.map_png.empty()) j.text("map", o.map_png);
  j.strings("outputs", result.outputs).number("seconds", result.seconds).print();
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
  app.add_option("IN", o->input, "mesh (OBJ, PLY, OFF, STL, glTF, GLB, optionally .gz); a saliency PLY or glTF brings its own saliency")->required();
  add_saliency_from_option(app, o->text);
  add_view_options(app, o->text);
  app.add_option("--views", o->views, "also evaluate N Fibonacci-sphere directions exhaustively (0: only with --map, 2000)")
      ->capture_default_str()->check(whole_in(0, meshsal::kMaxViewMapViews));
  app.add_option("-o,--output", o->out_png, "PNG of the mesh coloured by score from the best view");
  app.add_option("--map", o->map_png, "PNG of U over all directions (equirectangular)");
  add_picture_options(app, o->text, "side of the -o picture in pixels");
  app.add_option("--map-width", o->map_width, "width of the --map picture in pixels")
      ->capture_default_str()->check(whole_in(meshsal::kMinMapWidth, meshsal::kMaxImageSize));
  add_saliency_options(app, o->text);
  add_output_flags(app, o->text,
                   "Print the result as one JSON object on stdout (always so; accepted like the other commands' --json)");
  return [o]() { return run(*o); };
}

bool registered = register_command({"viewpoint", "best view direction by visible saliency (JSON), pictures", 60, setup});

}  // namespace
}  // namespace meshsal::cli
