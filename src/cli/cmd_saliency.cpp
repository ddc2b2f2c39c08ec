// meshsal saliency IN -o OUT.ply: the saliency map of one mesh file.
#include <algorithm>
#include <cstring>
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
#include "core/peak_memory.h"
#include "mpi_tile_exchange.h"
#include "mpi_world.h"

namespace meshsal_cli {
namespace {

struct Args {
  std::string precision = "auto";  // --precision
  std::string method = "exact";    // --method
  std::string input, output, backend = "auto", scales = "2,3,4,5,6";
  std::string memory_limit, temp_dir;  // --memory-limit, --temp-dir
  unsigned tiles = 0;                  // --tiles
  double eps_frac = 0.003;
  bool dump_scales = false, quiet = false, json = false;
  unsigned threads = 0;
  int device = -1;
};

// The largest peak resident memory over the ranks (this process's alone without MPI).
uint64_t peak_over_ranks() {
  const uint64_t mine = meshsal::peak_resident_bytes();
  std::vector<uint8_t> bytes(sizeof mine);
  std::memcpy(bytes.data(), &mine, sizeof mine);
  uint64_t most = 0;
  for (const auto& b : meshsal::cli::mpi_all_gather(bytes)) {
    uint64_t x = 0;
    if (b.size() == sizeof x) std::memcpy(&x, b.data(), sizeof x);
    most = std::max(most, x);
  }
  return most;
}

bool is_rank0() { return meshsal::cli::mpi_world().rank == 0; }

// Under mpirun, once this rank's own checks are done: the ranks meet (mpi_begin_work: one
// that failed before stops all, quietly), then every rank must run the same computation:
// rank 0's arguments are the run's.
void begin_work(const Args& a) {
  if (!meshsal::cli::mpi_world().active) return;
  meshsal::cli::mpi_begin_work();
  const std::string mine = a.input + "\n" + a.output + "\n" + a.method + "\n" + a.scales + "\n" +
                           std::to_string(a.eps_frac) + "\n" + std::to_string(a.tiles) + "\n" + a.memory_limit +
                           "\n" + std::to_string(a.dump_scales);
  const auto all = meshsal::cli::mpi_all_gather(std::vector<uint8_t>(mine.begin(), mine.end()));
  if (std::string(all[0].begin(), all[0].end()) != mine)
    throw meshsal::Error("the ranks were started with other arguments than rank 0's (this rank: " +
                         printable(a.input) + " -o " + printable(a.output) + ")");
}

// --memory-limit: the library streams the file through tiles on disk (saliency_file).
int run_out_of_core(const Args& a, const meshsal::SaliencyOptions& opt, Progress& progress) {
  using namespace meshsal;
  OutOfCoreOptions ooc;
  ooc.memory_limit = parse_memory_size(a.memory_limit);
  ooc.temp_dir = a.temp_dir;
  ooc.dump_scales = a.dump_scales;
  const meshsal::Timer t0;
  const OutOfCoreReport r = saliency_file(a.input, a.output, opt, ooc);
  progress.finish();
  const double seconds = t0.seconds();
  const uint64_t peak = peak_over_ranks();
  if (!is_rank0()) return 0;
  if (a.json) {
    out_of_core_json(a.input, a.output, r, opt.method, ooc.memory_limit, seconds, peak).print();
  } else if (!a.quiet) {
    std::printf("vertices   %llu (%llu on triangles)\n", (unsigned long long)r.vertices, (unsigned long long)r.points);
    std::printf("faces      %llu triangles\n", (unsigned long long)r.triangles);
    std::printf("eps        %.6g\n", r.eps);
    std::printf("tiles      %zu (largest estimated at %.0f MiB; peak resident %.0f MiB of %.0f MiB)\n", r.tiles,
                r.tile_estimate / 1048576.0, peak / 1048576.0, ooc.memory_limit / 1048576.0);
    for (const StageTime& s : r.stages) std::printf("%-10s %8.3f s\n", s.name.c_str(), s.seconds);
    std::printf("S          min %g, mean %g, max %g\n", r.saliency_min, r.saliency_mean, r.saliency_max);
    std::printf("wrote      %s\n", printable(a.output).c_str());
  }
  return 0;
}

int run(const Args& a) {
  using namespace meshsal;
  // Before any work: the output is a writable .ply, .glb or .gltf that is not the input.
  check_outputs({{a.output, "-o", {".ply", ".glb", ".gltf"}}}, {a.input});
  const bool gltf_out = meshsal::mesh_output_format(a.output) != ".ply";
  if (gltf_out && !a.memory_limit.empty())
    throw UsageError("--memory-limit writes a binary PLY: give -o OUT.ply");
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
  const bool quiet = a.quiet || !is_rank0();  // one voice under mpirun: rank 0's
  Progress progress(!quiet && stderr_is_terminal());
  opt.progress = [&](const char* stage, double f) { progress.update(stage, f); };
  opt.notice = [quiet](const std::string& line) {
    if (!quiet) std::fprintf(stderr, "%s\n", printable(line).c_str());
  };
  opt.tiles = a.tiles;
  opt.raw_maps = a.dump_scales;  // written only then; 8 bytes per vertex per scale otherwise
  // Under mpirun the ranks share the tiles; rank 0 writes and reports.
  MpiTileExchange exchange;
  if (meshsal::cli::mpi_world().active) {
    opt.exchange = &exchange;
    if (opt.tiles == 0 && a.memory_limit.empty()) opt.tiles = default_mpi_tiles(meshsal::cli::mpi_world().size);
  }
  check_saliency_options(opt);
  if (!a.memory_limit.empty()) {
    begin_work(a);
    return run_out_of_core(a, opt, progress);
  }

  const meshsal::Timer t0;
  progress.update("reading", 0.0);
  // A glTF output carries the input's normals, UVs and colours (and a glTF input's materials).
  Mesh mesh = load_input(a.input, quiet, nullptr, gltf_out);
  double load = t0.seconds();
  begin_work(a);  // after each rank read the input: one that cannot stops every rank alike
  SaliencyResult r = compute_saliency(mesh, opt);
  progress.update("writing", 0.0);
  if (is_rank0()) write_saliency_ply(a.output, mesh, r, a.dump_scales);
  progress.finish();
  const uint64_t peak = peak_over_ranks();
  if (!is_rank0()) return 0;
  if (a.json) {
    JsonObject j = saliency_json(a.input, a.output, mesh, r, load);
    j.count("peak_rss", peak);
    j.print();
  } else if (!a.quiet) {
    print_saliency_summary(mesh, r, load);
    std::printf("wrote      %s\n", printable(a.output).c_str());
  }
  return 0;
}

RunFn setup(CLI::App& sub) {
  auto a = std::make_shared<Args>();
  sub.footer(
      "Compute the mesh saliency of IN (OBJ, PLY, OFF, STL, glTF or GLB, optionally .gz) and\n"
      "write OUT.ply: binary PLY with the input positions and faces, per-vertex `quality`\n"
      "(saliency, read by MeshLab) and red/green/blue (low = blue, high = red). OUT.glb or\n"
      "OUT.gltf: glTF 2.0 with the saliency as the vertex attribute _SALIENCY and as COLOR_0 on\n"
      "the same colour scale, the input's normals, UVs and materials carried over.");
  sub.add_option("input", a->input, "Input mesh (.obj, .ply, .off, .stl, .gltf, .glb, optionally .gz)")->required();
  sub.add_option("-o,--output", a->output, "Output file: .ply, .glb or .gltf")->required();
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
  sub.add_option("--tiles", a->tiles,
                 "Compute in cubic tiles, N along the longest axis, each with a halo of the "
                 "filter's reach (exact: the same bits as without; fast: the same to 1e-4). With "
                 "--memory-limit: at least this many")
      ->check(whole_in(0, meshsal::kMaxTiles));
  sub.add_option("--memory-limit", a->memory_limit,
                 "Keep the peak resident memory under SIZE (e.g. 700M, 2G): the input (binary "
                 "PLY is streamed; other formats are read once and converted) goes to tiles on "
                 "disk, computed one at a time; too small a limit is an error naming the "
                 "smallest workable one. CPU only. " + std::string(kSizeSyntax))
      ->check(memory_size());
  add_temp_dir_option(sub, &a->temp_dir);
  sub.add_flag("--dump-scales", a->dump_scales,
               "Also write `curvature` and the raw maps saliency_raw_0.. as vertex properties");
  add_threads_option(sub, a->threads, "CPU threads (0 = all cores)");
  sub.add_flag("-q,--quiet", a->quiet, "Print nothing on success (no notes either)");
  sub.add_flag("--json", a->json,
               "Print the summary as one JSON object on stdout (mesh, device, seconds, stages, "
               "saliency min/mean/max/p10/p50/p90/p99)");
  return [a] { return run(*a); };
}

const bool registered = register_command({"saliency", "Compute the saliency map of a mesh file", 10, setup, true});

}  // namespace
}  // namespace meshsal_cli
