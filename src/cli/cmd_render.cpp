// `meshsal render`: a picture of the mesh coloured by saliency from any view, or side by side
// with simplified versions of it.
#include <cstdio>
#include <string>
#include <vector>

#include "command.h"
#include "meshsal/meshsal.h"
#include "view/render.h"
#include "api/viewpoint_score.h"
#include "number_options.h"
#include "output_check.h"
#include "progress.h"
#include "saliency_output.h"

namespace meshsal_cli {
namespace {

struct Options {
  std::string precision = "auto";  // --precision
  std::string method = "exact";    // --method
  std::string input, saliency_from, score = "saliency", output, backend = "auto";
  std::vector<std::string> compare;
  double theta_deg = 0, phi_deg = 0;
  int size = 512;
  bool grey = false, flat = false, edges = false;
  unsigned threads = 0;
};

int run(const Options& o) {
  using namespace meshsal;
  // Before any work: the picture is a writable .png that is none of the inputs.
  std::vector<std::string> inputs{o.input, o.saliency_from};
  inputs.insert(inputs.end(), o.compare.begin(), o.compare.end());
  check_outputs({{o.output, "-o", {".png"}}}, inputs);
  RenderStyle style;
  style.size = o.size;
  style.smooth = !o.flat && o.compare.empty();
  style.edges = o.edges;
  check_render_style(style);
  if (!o.compare.empty() && o.compare.size() != 2)
    throw Error("--compare takes two meshes: PLAIN SALIENT");
  const double rad = 3.14159265358979323846 / 180.0;
  ViewAngles view{o.theta_deg * rad, o.phi_deg * rad};

  Mesh mesh = load_mesh(o.input);
  std::vector<uint8_t> colours;
  if (!o.grey) {
    Progress progress(stderr_is_terminal());
    SaliencyOptions sopt;
    sopt.threads = o.threads;
    sopt.backend = parse_backend(o.backend);
    sopt.precision = meshsal::parse_precision(o.precision);
    sopt.method = meshsal::parse_method(o.method);
    sopt.progress = [&](const char* stage, double f) { progress.update(stage, f); };
    sopt.notice = [](const std::string& m) { std::fprintf(stderr, "%s\n", m.c_str()); };
    colours = score_colours(mesh, vertex_score(mesh, parse_view_score(o.score), o.saliency_from, sopt));
  }
  ViewFrame frame = frame_mesh(mesh);
  if (o.compare.empty()) {
    write_png(o.output, render_mesh(mesh, o.grey ? nullptr : &colours, frame, view, style));
    return 0;
  }
  Mesh plain = load_mesh(o.compare[0]);
  Mesh salient = load_mesh(o.compare[1]);
  write_png(o.output, render_side_by_side({&mesh, &plain, &salient},
                                          {o.grey ? nullptr : &colours, nullptr, nullptr}, frame, view, style));
  return 0;
}

RunFn setup(CLI::App& app) {
  auto o = std::make_shared<Options>();
  app.add_option("IN", o->input, "mesh (OBJ, PLY, OFF, optionally .gz)")->required();
  app.add_option("-o,--output", o->output, "PNG to write")->required();
  app.add_option("--theta", o->theta_deg, "view longitude in degrees (0 looks from +z, 90 from +x)")
      ->capture_default_str()->check(finite_in(-360, 360));
  app.add_option("--phi", o->phi_deg, "view latitude in degrees (90 looks from +y, above)")
      ->capture_default_str()->check(finite_in(-90, 90));
  app.add_option("--saliency-from", o->saliency_from, "PLY with per-vertex 'quality' instead of computing saliency");
  app.add_option("--score", o->score, "colour by saliency or curvature (|H|)")->capture_default_str();
  app.add_option("--compare", o->compare, "PLAIN SALIENT: two simplified meshes drawn right of IN, same camera")->expected(2);
  app.add_option("--size", o->size, "image side in pixels (per panel)")->capture_default_str()->check(whole_in(16, 8192));
  app.add_flag("--grey", o->grey, "no saliency colours");
  app.add_flag("--flat", o->flat, "flat shading (always on with --compare, shows the triangles)");
  app.add_flag("--edges", o->edges, "darken triangle edges");
  app.add_option("--backend", o->backend, "saliency backend: auto, gpu or cpu")->capture_default_str();
  add_precision_option(app, &o->precision);
  add_method_option(app, &o->method);
  add_threads_option(app, o->threads, "CPU threads, 0 = all cores");
  return [o]() { return run(*o); };
}

bool registered = register_command({"render", "PNG picture of a mesh coloured by saliency, or a side-by-side comparison", 70, setup});

}  // namespace
}  // namespace meshsal_cli
