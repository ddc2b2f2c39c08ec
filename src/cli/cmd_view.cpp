// `meshsal view IN -o page.html`: one self-contained HTML page that shows the model
// coloured by saliency in the browser (write_view_page), from the best view.
#include <cstdio>
#include <filesystem>
#include <string>

#include "api/viewpoint_score.h"
#include "command.h"
#include "core/timer.h"
#include "interrupt.h"
#include "json_object.h"
#include "json_string.h"
#include "load_input.h"
#include "meshsal/meshsal.h"
#include "number_options.h"
#include "output_check.h"
#include "own_saliency.h"
#include "progress.h"
#include "saliency_output.h"

namespace meshsal_cli {
namespace {

struct Options {
  std::string input, output, saliency_from, backend = "auto", method = "exact", precision = "auto", up = "y";
  std::string elevation;
  int device = -1;
  long long max_faces = 2000000;
  unsigned threads = 0;
  bool quiet = false, json = false;
};

int run(const Options& o) {
  using namespace meshsal;
  const Timer t0;
  check_outputs({{o.output, "-o", {".html"}}}, {o.input, o.saliency_from});
  if (!built_with_viewer())
    throw Error("this meshsal was built without the web viewer (web/node_modules was missing at build time: "
                "run tools/setup.sh, then build again)");
  VertexProperties props;
  Mesh mesh = load_input(o.input, o.quiet, &props);
  Progress progress(!o.quiet && stderr_is_terminal());
  SaliencyOptions so;
  so.cancel = interrupt_flag();
  so.threads = o.threads;
  so.backend = parse_backend(o.backend);
  so.precision = parse_precision(o.precision);
  so.method = parse_method(o.method);
  so.device = o.device;
  so.progress = [&](const char* stage, double f) { progress.update(stage, f); };
  so.notice = [&](const std::string& m) {
    if (!o.quiet) std::fprintf(stderr, "%s\n", printable(m).c_str());
  };
  std::string source;
  const std::vector<double> s =
      vertex_score(mesh, ViewScore::Saliency, saliency_source_file(o.input, props, o.saliency_from, true), so, &source);
  ViewpointOptions vo;
  vo.up = parse_up_axis(o.up);
  if (!o.elevation.empty()) vo.elevation = parse_elevation_range(o.elevation);
  vo.threads = o.threads;
  vo.backend = so.backend;
  vo.device = o.device;
  vo.progress = so.progress;
  vo.notice = so.notice;
  vo.cancel = interrupt_flag();
  const Viewpoint best = best_viewpoint(mesh, s, vo);
  progress.update("writing", 0.0);
  ViewPageOptions po;
  po.title = std::filesystem::path(o.input).filename().string();
  po.max_faces = size_t(o.max_faces);
  po.stats = view_page_stats(mesh, s, source.empty() ? "computed" : source, t0.seconds());
  const ViewPageReport page = write_view_page(o.output, mesh, s, best.camera, po);
  progress.finish();
  if (o.json) {
    JsonObject j;
    j.text("mesh", o.input).text("output", o.output).count("vertices", mesh.vertex_count())
        .count("faces", mesh.triangle_count()).flag("simplified_copy", page.simplified)
        .count("shown_faces", page.shown_faces);
    if (page.simplified) j.count("max_faces", po.max_faces).flag("max_faces_reached", page.within_max_faces);
    j.number("seconds", t0.seconds()).print();
  } else if (!o.quiet) {
    if (page.simplified && page.within_max_faces)
      std::printf("note       the page shows a copy simplified to %zu faces (the mesh has %zu)\n", page.shown_faces,
                  mesh.triangle_count());
    else if (page.simplified)
      std::printf("note       the page shows a copy simplified to %zu faces, not the %zu of --max-faces: the "
                  "simplifier could go no further (the mesh has %zu)\n", page.shown_faces, po.max_faces,
                  mesh.triangle_count());
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
      "the summary say how many. A saliency PLY (from `meshsal saliency`) brings its own saliency.");
  sub.add_option("IN", o->input, "mesh (OBJ, PLY, OFF, STL, glTF, GLB, optionally .gz)")->required();
  sub.add_option("-o,--output", o->output, "the page (.html)")->required();
  sub.add_option("--saliency-from", o->saliency_from, "Reuse S from this saliency PLY (`quality` property)");
  sub.add_option("--max-faces", o->max_faces, "Show a simplified copy of a larger mesh (0 = never)")
      ->capture_default_str()->check(whole_in(0, 4000000000LL));
  sub.add_option("--up", o->up, "The model's up axis: x, y, z, -x, -y or -z")->capture_default_str();
  add_elevation_option(sub, &o->elevation);
  sub.add_option("--backend", o->backend, "Saliency and view backend: auto, cpu or gpu")->capture_default_str();
  add_precision_option(sub, &o->precision);
  add_method_option(sub, &o->method);
  sub.add_option("--device", o->device, "Vulkan device index (see `meshsal devices`)")->check(whole_in(-1, 255));
  add_threads_option(sub, o->threads, "CPU threads (0 = all cores)");
  sub.add_flag("-q,--quiet", o->quiet, "Print nothing on success");
  sub.add_flag("--json", o->json, "Print the summary as one JSON object on stdout");
  return [o] { return run(*o); };
}

const bool registered =
    register_command({"view", "HTML page that shows a mesh's saliency in the browser (three.js, offline)", 65, setup});

}  // namespace
}  // namespace meshsal_cli
