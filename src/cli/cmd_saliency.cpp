// meshsal saliency IN -o OUT.ply: the saliency map of one mesh file.
#include <algorithm>
#include <cstring>
#include <memory>

#include "core/parallel.h"
#include "command.h"
#include "json_string.h"
#include "core/timer.h"
#include "meshsal/meshsal.h"
#include "saliency/saliency.h"
#include "number_options.h"
#include "output_check.h"
#include "load_input.h"
#include "progress.h"
#include "request_options.h"
#include "saliency_output.h"
#include "interrupt.h"
#include "core/peak_memory.h"
#include "mpi_tile_exchange.h"
#include "mpi_world.h"

namespace meshsal::cli {
namespace {

struct Args {
  std::string input, output;
  unsigned tiles = 0;  // --tiles
  bool dump_scales = false;
  RequestText text;    // the options every command shares
};

bool is_rank0() { return meshsal::cli::mpi_world().rank == 0; }

// Under mpirun: every rank runs rank 0's computation (begin_shared_work).
void begin_work(const Args& a) {
  const RequestText& t = a.text;
  begin_shared_work(a.input + "\n" + a.output + "\n" + t.method + "\n" + t.scales + "\n" + std::to_string(t.eps_frac) +
                        "\n" + std::to_string(a.tiles) + "\n" + t.memory_limit + "\n" + std::to_string(a.dump_scales),
                    printable(a.input) + " -o " + printable(a.output));
}

void print_out_of_core(const Args& a, const meshsal::OutOfCoreReport& r, meshsal::Method method, uint64_t limit,
                       uint64_t peak) {
  std::printf("vertices   %llu (%llu on triangles)\n", (unsigned long long)r.vertices, (unsigned long long)r.points);
  std::printf("faces      %llu triangles\n", (unsigned long long)r.triangles);
  std::printf("eps        %.6g\n", r.eps);
  std::printf("tiles      %zu (largest estimated at %.0f MiB; peak resident %.0f MiB of %.0f MiB)%s\n", r.tiles,
              r.tile_estimate / 1048576.0, peak / 1048576.0, limit / 1048576.0,
              r.ranks > 1 ? (", shared by " + std::to_string(r.ranks) + " ranks").c_str() : "");
  std::printf("method     %s\n", method == meshsal::Method::Exact
                                       ? "exact"
                                       : "fast (cell aggregates; error against exact: docs/method.md)");
  double total = 0;
  for (const meshsal::StageTime& s : r.stages) {
    std::printf("%-10s %8.3f s\n", s.name.c_str(), s.seconds);
    total += s.seconds;
  }
  std::printf("total      %8.3f s, %.3g neighbour pairs (halos included)\n", total, double(r.pairs));
  std::printf("S          min %g, mean %g, max %g; percentiles 10: %g, 50: %g, 90: %g, 99: %g\n", r.saliency_min,
              r.saliency_mean, r.saliency_max, r.saliency_p10, r.saliency_p50, r.saliency_p90, r.saliency_p99);
  std::printf("wrote      %s\n", printable(a.output).c_str());
}

int run(Args a) {
  using namespace meshsal;
  a.text.quiet = a.text.quiet || !is_rank0();  // one voice under mpirun: rank 0's
  Progress progress(!a.text.quiet && stderr_is_terminal());
  Request r = request_from(a.text, &progress);
  r.input = a.input;
  r.saliency_output = a.output;
  r.dump_scales = a.dump_scales;
  r.saliency.tiles = a.tiles;
  // Under mpirun the ranks share the tiles; rank 0 writes and reports.
  MpiTileExchange exchange;
  if (meshsal::cli::mpi_world().active) {
    r.saliency.exchange = &exchange;
    if (r.saliency.tiles == 0 && a.text.memory_limit.empty()) r.saliency.tiles = default_mpi_tiles(meshsal::cli::mpi_world().size);
  }
  // After each rank read the input: one that cannot stops every rank alike.
  r.on_read = [&a] { begin_work(a); };
  const RequestResult result = run_request(r);
  progress.finish();
  const uint64_t peak = max_over_ranks(meshsal::peak_resident_bytes());
  if (!is_rank0()) return 0;
  if (r.out_of_core.memory_limit > 0) {
    if (a.text.json)
      out_of_core_json(a.input, a.output, result.out_of_core, r.saliency.method, r.out_of_core.memory_limit, result.seconds, peak)
          .count("threads_per_rank", resolve_threads(r.saliency.threads))
          .print();
    else if (!a.text.quiet)
      print_out_of_core(a, result.out_of_core, r.saliency.method == Method::Exact ? Method::Exact : Method::Fast,
                        r.out_of_core.memory_limit, peak);
    return 0;
  }
  if (a.text.json) {
    JsonObject j = saliency_json(a.input, a.output, result.mesh, result.saliency, result.load_seconds);
    j.count("peak_rss", peak).count("threads_per_rank", resolve_threads(r.saliency.threads));
    if (result.upload_while_reading > 0) j.number("upload_while_reading_seconds", result.upload_while_reading);
    j.strings("outputs", result.outputs);
    j.print();
  } else if (!a.text.quiet) {
    print_saliency_summary(result.mesh, result.saliency, result.load_seconds);
    for (const std::string& f : result.outputs) std::printf("wrote      %s\n", printable(f).c_str());
  }
  return 0;
}

RunFn setup(CLI::App& sub) {
  auto a = std::make_shared<Args>();
  sub.footer(
      "Compute the mesh saliency of IN (OBJ, PLY, OFF, STL, glTF or GLB, optionally .gz) and\n"
      "write it with the mesh. OUT.ply: binary PLY with the input positions and faces, per-vertex\n"
      "`quality` (saliency, read by MeshLab) and red/green/blue (low = blue, high = red). OUT.glb\n"
      "or OUT.gltf: glTF 2.0 with the saliency as the vertex attribute _SALIENCY and as COLOR_0\n"
      "on the same colour scale, the input's normals, UVs and materials carried over. OUT.obj\n"
      "(v x y z r g b, with its .mtl) and OUT.off (COFF) keep the saliency's colours only, with a\n"
      "note; STL keeps none and is refused.");
  sub.add_option("input", a->input, "Input mesh (.obj, .ply, .off, .stl, .gltf, .glb, optionally .gz)")->required();
  sub.add_option("-o,--output", a->output, "Output file: .ply, .glb, .gltf, .obj or .off")->required();
  add_saliency_options(sub, a->text);
  sub.add_option("--tiles", a->tiles,
                 "Compute in cubic tiles, N along the longest axis, each with a halo of the "
                 "filter's reach (exact: the same bits as without; fast: the same to 1e-4). With "
                 "--memory-limit: at least this many")
      ->check(whole_in(0, meshsal::kMaxTiles));
  add_memory_options(sub, a->text,
                     "Keep the peak resident memory under SIZE (e.g. 700M, 2G): the input (binary "
                     "PLY is streamed; other formats are read once and converted) goes to tiles on "
                     "disk, computed one at a time; too small a limit is an error naming the "
                     "smallest workable one. CPU only.");
  sub.add_flag("--dump-scales", a->dump_scales,
               "Also write `curvature` and the raw maps saliency_raw_0.. as vertex properties (--model "
               "perceptual: its cues cue_exposure_centre, cue_height, cue_rarity, cue_coarse)");
  add_output_flags(sub, a->text,
                   "Print the summary as one JSON object on stdout (mesh, device, seconds, stages, "
                   "saliency min/mean/max/p10/p50/p90/p99, outputs)");
  return [a] { return run(*a); };
}

const bool registered = register_command({"saliency", "Compute the saliency map of a mesh file", 10, setup, true});

}  // namespace
}  // namespace meshsal::cli
