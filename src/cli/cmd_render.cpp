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
#include "view/picture.h"
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
  std::string input, output;
  std::vector<std::string> compare;
  double theta_deg = 0, phi_deg = 0;
  bool grey = false, flat = false, edges = false, best = false;
  RequestText text;  // the options every command shares
};

int run(const Options& o) {
  using namespace meshsal;
  Progress progress(!o.text.quiet && stderr_is_terminal());
  Request r = request_from(o.text, &progress);
  r.input = o.input;
  r.picture_output = o.output;
  r.compare = o.compare;
  r.grey = o.grey;
  r.find_view = o.best;
  r.saliency_from_input = true;  // a saliency PLY or glTF brings its own S
  const double rad = 3.14159265358979323846 / 180.0;
  r.view = ViewAngles{o.theta_deg * rad, o.phi_deg * rad};
  r.style.smooth = !o.flat && o.compare.empty();
  r.style.edges = o.edges;
  const RequestResult result = run_request(r);
  progress.finish();
  if (o.best && !o.text.quiet) std::fprintf(stderr, "best view: %s\n", view_text(result.view, r.style.up).c_str());
  if (!o.text.json) {
    // One line, as the other commands say what they wrote (stdout; --json replaces it).
    if (!o.text.quiet) std::printf("wrote %s (%dx%d)\n", printable(o.output).c_str(), result.picture_width, result.picture_height);
    return 0;
  }
  // The view in the angles of --up; visible_score = U of the original as the title gives it
  // (CPU visibility at 512 px), null without a score (--grey).
  const bool shown = !o.grey;
  JsonObject j;
  j.text("mesh", o.input).text("output", o.output).count("vertices", result.mesh.vertex_count())
      .count("faces", result.mesh.triangle_count())
      .text("device", o.best ? result.viewpoint.backend_name : "cpu").text("up", o.text.up).flag("best", o.best);
  add_view(j, frame_mesh(result.mesh, r.style.up), result.view);
  if (shown)
    j.text("score", o.text.score).text("score_source", result.saliency_source).number("visible_score", result.visible_score)
        .number("visible_fraction", result.visible_total > 0 ? result.visible_score / result.visible_total : 0.0);
  else
    j.null("score").null("score_source").null("visible_score").null("visible_fraction");
  if (!o.compare.empty()) j.text("plain", o.compare[0]).text("salient", o.compare[1]);
  j.strings("outputs", result.outputs).number("seconds", result.seconds).print();
  return 0;
}

RunFn setup(CLI::App& app) {
  auto o = std::make_shared<Options>();
  app.add_option("IN", o->input, "mesh (OBJ, PLY, OFF, STL, glTF, GLB, optionally .gz); a saliency PLY or glTF brings its own saliency")->required();
  app.add_option("-o,--output", o->output, "PNG to write")->required();
  auto* theta = app.add_option("--theta", o->theta_deg, "view longitude in degrees (0 looks from the front, 90 from the right)")
      ->capture_default_str()->check(finite_in(-360, 360));
  auto* phi = app.add_option("--phi", o->phi_deg, "view latitude in degrees (90 looks from above)")
      ->capture_default_str()->check(finite_in(-90, 90));
  auto* best = app.add_flag("--best", o->best, "render the view of most visible saliency (as `meshsal viewpoint` finds it)")
      ->excludes(theta)->excludes(phi);
  // The search's own options apply with --best; --up and --score to every picture.
  for (CLI::Option* option : add_view_options(app, o->text))
    if (option->get_name() != "--up" && option->get_name() != "--score") option->needs(best);
  add_saliency_from_option(app, o->text);
  app.add_option("--compare", o->compare,
                 "PLAIN SALIENT: two simplified meshes drawn right of IN, same camera, coloured by distance to IN")
      ->expected(2);
  add_picture_options(app, o->text, "image side in pixels (per panel)");
  app.add_flag("--grey", o->grey, "no saliency colours");
  app.add_flag("--flat", o->flat, "flat shading (always on with --compare, shows the triangles)");
  app.add_flag("--edges", o->edges, "darken triangle edges");
  add_saliency_options(app, o->text);
  add_output_flags(app, o->text,
                   "Print one JSON object on stdout: mesh, output, device, the view's angles (theta, phi, "
                   "theta_deg, phi_deg, direction), visible_score U and visible_fraction, outputs, seconds");
  return [o]() { return run(*o); };
}

bool registered = register_command({"render", "PNG picture of a mesh coloured by saliency, or a side-by-side comparison", 70, setup});

}  // namespace
}  // namespace meshsal::cli
