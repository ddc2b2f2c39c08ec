// meshsal compare ORIGINAL SIMPLIFIED: surface distances between a mesh and its simplification.
#include <cstdio>
#include <utility>
#include <memory>
#include <string>

#include "command.h"
#include "json_string.h"
#include "core/timer.h"
#include "meshsal/meshsal.h"
#include "saliency/saliency.h"
#include "simplify/saliency_weights.h"
#include "core/surface_distance.h"
#include "json_object.h"
#include "load_input.h"
#include "number_options.h"
#include "progress.h"
#include "request_options.h"
#include "saliency_output.h"
#include "interrupt.h"

namespace meshsal::cli {
namespace {

struct Args {
  std::string original, simplified;
  long long samples = 200000;
  double fraction = 0.30;
  RequestText text;  // the options every command shares (--json: the output is always JSON)
};

int run(const Args& a) {
  using namespace meshsal;
  const meshsal::Timer t0;
  Progress progress(!a.text.quiet && stderr_is_terminal());  // on stderr: stdout holds only the JSON
  progress.update("reading", 0.0);
  const Mesh original = load_input(a.original, a.text.quiet);
  const Mesh simplified = load_input(a.simplified, a.text.quiet);
  std::vector<double> s;
  std::string source, device = "cpu";  // distances are measured on the CPU
  if (!a.text.saliency_from.empty()) {
    s = load_saliency(a.text.saliency_from, original);
    source = a.text.saliency_from;
  } else {
    // The saliency options as every command reads them (request_from).
    SaliencyOptions so = request_from(a.text, &progress).saliency;
    so.raw_maps = false;
    SaliencyResult r = compute_saliency(original, so);
    s = std::move(r.saliency);
    source = "computed (" + r.backend_name + ")";
    device = r.backend_name;
  }
  CompareOptions co;
  co.cancel = interrupt_flag();
  co.face_samples = size_t(a.samples);
  co.salient_fraction = a.fraction;
  co.threads = a.text.threads;
  progress.update("comparing surfaces", 0.0);
  const SurfaceComparison r = compare_surfaces(original, simplified, s, co);
  progress.finish();
  // Every distance in model units and in % of the original's bounding-box diagonal.
  JsonObject j;
  j.text("mesh", a.original).text("original", a.original).text("simplified", a.simplified)
      .count("original_faces", original.triangle_count()).count("simplified_faces", simplified.triangle_count())
      .number("diagonal", r.diagonal);
  const std::pair<const char*, double> distances[] = {
      {"hausdorff", r.hausdorff},       {"rms", r.rms},
      {"forward_max", r.forward_max},   {"forward_rms", r.forward_rms},
      {"backward_max", r.backward_max}, {"backward_rms", r.backward_rms},
      {"salient_error", r.salient_error}};
  for (const auto& [name, d] : distances) j.number(name, d);
  for (const auto& [name, d] : distances)
    j.number(std::string(name) + "_percent", r.diagonal > 0 ? 100.0 * d / r.diagonal : 0.0);
  j.count("salient_vertices", r.salient_vertices).number("salient_fraction", a.fraction).text("saliency_source", source)
      .text("device", device)
      .count("forward_samples", r.forward_samples).count("backward_samples", r.backward_samples)
      .number("seconds", t0.seconds());
  j.print();
  return 0;
}

RunFn setup(CLI::App& sub) {
  auto a = std::make_shared<Args>();
  sub.footer(
      "Print one JSON object with the symmetric Hausdorff and RMS distances between ORIGINAL\n"
      "and SIMPLIFIED (point-to-triangle over a BVH; each surface sampled at its vertices plus\n"
      "--samples area-spread points; symmetric = the larger of the two directions) and the\n"
      "salient-region error: the mean distance from the original's top 30% most salient\n"
      "vertices to the simplified surface. Saliency comes from --saliency FILE.ply or is\n"
      "computed. Distances are in model units, and as NAME_percent in % of `diagonal`, the\n"
      "original's bounding-box diagonal. forward = from ORIGINAL's surface to SIMPLIFIED's,\n"
      "backward = from SIMPLIFIED's to ORIGINAL's. saliency_source: the file or `computed\n"
      "(DEVICE)`; device: where saliency was computed (cpu when read: distances run on the CPU).");
  sub.add_option("original", a->original, "The original mesh")->required();
  sub.add_option("simplified", a->simplified, "The simplified mesh")->required();
  add_saliency_from_option(sub, a->text, "--saliency-from,--saliency");
  sub.add_option("--samples", a->samples, "Area samples per surface besides its vertices")
      ->capture_default_str()->check(whole_in(0, 100000000));
  sub.add_option("--salient-fraction", a->fraction, "Fraction of most salient vertices")
      ->capture_default_str()->check(finite_in(0, 1, true));
  add_saliency_options(sub, a->text);
  add_output_flags(sub, a->text,
                   "Print the result as one JSON object on stdout (always so; accepted like the other commands' --json); "
                   "-q: no progress or notes");
  return [a] { return run(*a); };
}

const bool registered = register_command(
    {"compare", "Hausdorff, RMS and salient-region error of a simplified mesh", 25, setup});

}  // namespace
}  // namespace meshsal::cli
