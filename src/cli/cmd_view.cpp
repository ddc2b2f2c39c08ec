// `meshsal view IN -o page.html`: one self-contained HTML page that shows the model
// coloured by saliency in the browser (write_view_page), from the best view.
#include <cstdio>
#include <filesystem>
#include <string>

#include "command.h"
#include "core/timer.h"
#include "interrupt.h"
#include "json_object.h"
#include "json_string.h"
#include "load_input.h"
#include "meshsal/meshsal.h"
#include "number_options.h"
#include "output_check.h"
#include "progress.h"
#include "request_options.h"
#include "view/camera.h"
#include "view/picture.h"
#include "view_json.h"

namespace meshsal::cli {
namespace {

struct Options {
  std::string input, output;
  long long max_faces = 2000000;
  RequestText text;  // the options every command shares
};

int run(const Options& o) {
  using namespace meshsal;
  Progress progress(!o.text.quiet && stderr_is_terminal());
  Request r = request_from(o.text, &progress);
  r.input = o.input;
  r.page_output = o.output;
  r.page.max_faces = size_t(o.max_faces);
  r.saliency_from_input = true;  // a saliency PLY or glTF brings its own S
  r.find_view = true;
  const RequestResult result = run_request(r);
  progress.finish();
  const ViewPageReport& page = result.page;
  if (o.text.json) {
    JsonObject j;
    j.text("mesh", o.input).text("output", o.output).count("vertices", result.mesh.vertex_count())
        .count("faces", result.mesh.triangle_count()).flag("simplified_copy", page.simplified)
        .count("shown_faces", page.shown_faces);
    if (page.simplified) j.count("max_faces", r.page.max_faces).flag("max_faces_reached", page.within_max_faces);
    add_view(j, frame_mesh(result.mesh, r.viewpoint.up), result.view);
    j.number("visible_score", result.viewpoint.U).number("visible_fraction", result.viewpoint.visible_fraction)
        .text("score", o.text.score).text("score_source", result.saliency_source)
        .strings("outputs", result.outputs).number("seconds", result.seconds).print();
  } else if (!o.text.quiet) {
    std::printf("best view  %s\n", view_text(result.view, r.viewpoint.up).c_str());
    std::printf("wrote      %s\n", printable(o.output).c_str());
  }
  return 0;
}

RunFn setup(CLI::App& sub) {
  auto o = std::make_shared<Options>();
  sub.footer(
      "Write one self-contained HTML page (no network needed to open it) that shows IN coloured by\n"
      "saliency in the browser: the colour bar and its scale, orbit controls, the best view as the\n"
      "starting camera, a toggle between saliency, plain shading and wireframe, and the statistics.\n"
      "The mesh is embedded as GLB; a mesh over --max-faces faces is shown as a copy simplified to\n"
      "that many (or as few as the simplifier reaches: a closed surface keeps 4) and the page and\n"
      "the summary say how many. A saliency PLY or glTF (from `meshsal saliency`) brings its own\n"
      "saliency.");
  sub.add_option("IN", o->input, "mesh (OBJ, PLY, OFF, STL, glTF, GLB, optionally .gz)")->required();
  sub.add_option("-o,--output", o->output, "the page (.html)")->required();
  add_saliency_from_option(sub, o->text);
  sub.add_option("--max-faces", o->max_faces, "Show a simplified copy of a larger mesh (0 = never)")
      ->capture_default_str()->check(whole_in(0, 4000000000LL));
  add_view_options(sub, o->text);
  add_color_range_option(sub, o->text);
  add_saliency_options(sub, o->text);
  add_output_flags(sub, o->text, "Print the summary as one JSON object on stdout");
  return [o] { return run(*o); };
}

const bool registered =
    register_command({"view", "HTML page that shows a mesh's saliency in the browser (three.js, offline)", 65, setup});

}  // namespace
}  // namespace meshsal::cli
