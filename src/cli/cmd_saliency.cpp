// meshsal saliency IN -o OUT.ply: the saliency map of one mesh file.
#include <memory>

#include "command.h"
#include "json_string.h"
#include "core/timer.h"
#include "meshsal/meshsal.h"
#include "saliency/saliency.h"
#include "number_options.h"
#include "output_check.h"
#include "load_input.h"
#include "progress.h"
#include "saliency_output.h"
#include "interrupt.h"

namespace meshsal_cli {
namespace {

struct Args {
  std::string precision = "auto";  // --precision
  std::string method = "exact";    // --method
  std::string input, output, backend = "auto", scales = "2,3,4,5,6";
  double eps_frac = 0.003;
  bool dump_scales = false, quiet = false, json = false;
  unsigned threads = 0;
  int device = -1;
};

int run(const Args& a) {
  using namespace meshsal;
  // Before any work: the output is a writable .ply that is not the input.
  check_outputs({{a.output, "-o", {".ply"}}}, {a.input});
  SaliencyOptions opt;
  opt.cancel = interrupt_flag();
  opt.eps_frac = a.eps_frac;
  opt.scales = parse_scales(a.scales);
  opt.threads = a.threads;
  opt.backend = parse_backend(a.backend);
  opt.precision = meshsal::parse_precision(a.precision);
  opt.method = meshsal::parse_method(a.method);
  opt.device = a.device;
  check_saliency_options(opt);
  Progress progress(!a.quiet && stderr_is_terminal());
  opt.progress = [&](const char* stage, double f) { progress.update(stage, f); };
  opt.notice = [&a](const std::string& line) {
    if (!a.quiet) std::fprintf(stderr, "%s\n", printable(line).c_str());
  };

  const meshsal::Timer t0;
  progress.update("reading", 0.0);
  Mesh mesh = load_input(a.input, a.quiet);
  double load = t0.seconds();
  SaliencyResult r = compute_saliency(mesh, opt);
  progress.update("writing", 0.0);
  write_saliency_ply(a.output, mesh, r, a.dump_scales);
  progress.finish();
  if (a.json) {
    print_saliency_json(a.input, a.output, mesh, r, load);
  } else if (!a.quiet) {
    print_saliency_summary(mesh, r, load);
    std::printf("wrote      %s\n", printable(a.output).c_str());
  }
  return 0;
}

RunFn setup(CLI::App& sub) {
  auto a = std::make_shared<Args>();
  sub.footer(
      "Compute the mesh saliency of IN (OBJ, PLY, OFF or STL, optionally .gz) and write OUT.ply:\n"
      "binary PLY with the input positions and faces, per-vertex `quality` (saliency, read by\n"
      "MeshLab) and red/green/blue (low = blue, high = red).");
  sub.add_option("input", a->input, "Input mesh (.obj, .ply, .off, .stl, optionally .gz)")->required();
  sub.add_option("-o,--output", a->output, "Output PLY file")->required();
  sub.add_option("--backend", a->backend,
                 "auto (a GPU when present, else the CPU), gpu (any Vulkan device, lavapipe "
                 "included) or cpu")->capture_default_str();
  add_precision_option(sub, &a->precision);
  add_method_option(sub, &a->method);
  sub.add_option("--device", a->device, "Vulkan device index for the gpu backend (see `meshsal devices`)")->check(whole_in(-1, 255));
  sub.add_option("--scales", a->scales,
                 "Center-surround scales in units of eps: scale k compares the Gaussian averages "
                 "of curvature at k*eps and 2k*eps")->capture_default_str()->check(scales_list());
  sub.add_option("--eps-frac", a->eps_frac, "eps as a fraction of the bounding-box diagonal")
      ->capture_default_str()->check(finite_in(0, meshsal::kMaxEpsFrac, true));
  sub.add_flag("--dump-scales", a->dump_scales,
               "Also write `curvature` and the raw maps saliency_raw_0.. as vertex properties");
  add_threads_option(sub, a->threads, "CPU threads (0 = all cores)");
  sub.add_flag("-q,--quiet", a->quiet, "Print nothing on success (no notes either)");
  sub.add_flag("--json", a->json,
               "Print the summary as one JSON object on stdout (mesh, device, seconds, stages, "
               "saliency min/mean/max/p10/p50/p90/p99)");
  return [a] { return run(*a); };
}

const bool registered = register_command({"saliency", "Compute the saliency map of a mesh file", 10, setup});

}  // namespace
}  // namespace meshsal_cli
