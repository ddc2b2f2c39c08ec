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
#include "simplify/surface_distance.h"
#include "json_object.h"
#include "load_input.h"
#include "number_options.h"
#include "progress.h"
#include "saliency_output.h"
#include "interrupt.h"

namespace meshsal_cli {
namespace {

struct Args {
  std::string precision = "auto";  // --precision
  std::string method = "exact";    // --method
  std::string original, simplified, saliency, backend = "auto";
  long long samples = 200000;
  double fraction = 0.30;
  unsigned threads = 0;
  bool json = false;  // accepted like every command's --json; the output is always JSON
  bool quiet = false;  // -q: no progress or notes (the result is printed)
};

int run(const Args& a) {
  using namespace meshsal;
  const meshsal::Timer t0;
  Progress progress(!a.quiet && stderr_is_terminal());  // on stderr: stdout holds only the JSON
  progress.update("reading", 0.0);
  const Mesh original = load_input(a.original, a.quiet);
  const Mesh simplified = load_input(a.simplified, a.quiet);
  std::vector<double> s;
  std::string source, device = "cpu";  // distances are measured on the CPU
  if (!a.saliency.empty()) {
    s = load_saliency_ply(a.saliency, original);
    source = a.saliency;
  } else {
    SaliencyOptions so;
    so.cancel = interrupt_flag();
    so.backend = parse_backend(a.backend);
    so.precision = meshsal::parse_precision(a.precision);
    so.method = meshsal::parse_method(a.method);
    so.threads = a.threads;
    so.raw_maps = false;
    so.notice = [&a](const std::string& line) {
      if (!a.quiet) std::fprintf(stderr, "%s\n", printable(line).c_str());
    };
    so.progress = [&](const char* stage, double f) { progress.update(stage, f); };
    SaliencyResult r = compute_saliency(original, so);
    s = std::move(r.saliency);
    source = "computed (" + r.backend_name + ")";
    device = r.backend_name;
  }
  CompareOptions co;
  co.cancel = interrupt_flag();
  co.face_samples = size_t(a.samples);
  co.salient_fraction = a.fraction;
  co.threads = a.threads;
  progress.update("comparing surfaces", 0.0);
  const SurfaceComparison r = compare_surfaces(original, simplified, &s, co);
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
  sub.add_option("--saliency-from,--saliency", a->saliency,
                 "Reuse S from this saliency PLY of the original (`meshsal saliency`) instead of computing it");
  sub.add_option("--samples", a->samples, "Area samples per surface besides its vertices")
      ->capture_default_str()->check(whole_in(0, 100000000));
  sub.add_option("--salient-fraction", a->fraction, "Fraction of most salient vertices")
      ->capture_default_str()->check(finite_in(0, 1, true));
  sub.add_option("--backend", a->backend, "Saliency backend: auto, cpu or gpu")->capture_default_str();
  add_precision_option(sub, &a->precision);
  add_method_option(sub, &a->method);
  add_threads_option(sub, a->threads, "Threads (0 = all cores)");
  sub.add_flag("--json", a->json,
               "Print the result as one JSON object on stdout (always so; accepted like the other commands' --json)");
  sub.add_flag("-q,--quiet", a->quiet, "No progress or notes on stderr (the result is still printed)");
  return [a] { return run(*a); };
}

const bool registered = register_command(
    {"compare", "Hausdorff, RMS and salient-region error of a simplified mesh", 25, setup});

}  // namespace
}  // namespace meshsal_cli
