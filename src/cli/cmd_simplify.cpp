// meshsal simplify IN -o OUT: Garland-Heckbert simplification, saliency-weighted by default.
#include <algorithm>
#include <cstdio>
#include <memory>

#include "command.h"
#include "json_string.h"
#include "core/mesh_points.h"
#include "core/timer.h"
#include "meshsal/meshsal.h"
#include "simplify/simplify.h"
#include "number_options.h"
#include "output_check.h"
#include "json_object.h"
#include "load_input.h"
#include "progress.h"
#include "request_options.h"
#include "saliency_output.h"
#include "interrupt.h"
#include "mpi_tile_exchange.h"
#include "mpi_world.h"
#include "core/parallel.h"
#include "core/peak_memory.h"

namespace meshsal::cli {
namespace {

struct Args {
  std::string input, output;
  long long target_faces = 0;
  double ratio = 0;
  double target_error = 0;  // --target-error, % of the bounding-box diagonal
  bool has_target = false, has_ratio = false, lock_border = false;
  long long tiles = 0;  // --tiles: 0 = not given (one piece)
  std::string lod;      // --lod: ratios or face counts
  RequestText text;     // the options every command shares
};

// --memory-limit: the library streamed the file through tiles on disk (simplify_file).
// Under mpirun: every rank runs rank 0's computation (begin_shared_work).
void begin_work(const Args& a) {
  const RequestText& t = a.text;
  begin_shared_work(a.input + "\n" + a.output + "\n" + std::to_string(a.target_faces) + "\n" + std::to_string(a.ratio) +
                        "\n" + std::to_string(a.tiles) + "\n" + std::to_string(a.lock_border) + "\n" +
                        t.memory_limit + "\n" + t.weights + "\n" + std::to_string(t.lambda) + "\n" +
                        std::to_string(t.alpha_percentile) + "\n" + std::to_string(t.weight_floor) + "\n" + t.method +
                        "\n" + t.scales + "\n" + std::to_string(t.eps_frac) + "\n" + t.saliency_from,
                    printable(a.input) + " -o " + printable(a.output));
}

// ", shared by N ranks" under mpirun (the summary's tiles line).
std::string shared_by() {
  const int n = mpi_world().size;
  return n > 1 ? ", shared by " + std::to_string(n) + " ranks" : "";
}

void print_out_of_core(const Args& a, const meshsal::Request& r, const meshsal::RequestResult& result, uint64_t peak) {
  using namespace meshsal;
  const OutOfCoreSimplifyReport& ooc = result.simplify_out_of_core;
  const SimplifyReport& rep = ooc.simplify;
  const bool weighted = r.weighting != Weighting::None;
  const SaliencyWeightOptions& wo = r.weight_options;
  if (a.text.json) {
    JsonObject j;
    j.text("mesh", a.input).text("output", a.output).count("input_vertices", size_t(ooc.saliency.vertices))
        .count("input_faces", rep.input_faces).count("output_vertices", rep.output_vertices)
        .count("output_faces", rep.output_faces).count("target_faces", rep.target_faces)
        .flag("unchanged", rep.unchanged).count("collapses", rep.collapses).flag("reached", rep.reached)
        .text("weights", a.text.weights).text("device", "cpu").number("error_percent", 100 * rep.error)
        .flag("lock_border", a.lock_border).count("tiles", ooc.tiles).count("saliency_tiles", ooc.saliency.tiles)
        .count("memory_limit", size_t(r.out_of_core.memory_limit)).count("tile_estimate", size_t(ooc.tile_estimate))
        .count("groups_at_once", ooc.groups_at_once).count("peak_rss", size_t(peak)).count("ranks", size_t(mpi_world().size))
        .count("threads_per_rank", resolve_threads(r.saliency.threads));
    if (weighted) j.number("lambda", wo.lambda).number("alpha", ooc.alpha).number("alpha_percentile", wo.alpha_percentile);
    j.strings("outputs", result.outputs).number("seconds", result.seconds).print();
  } else if (!a.text.quiet) {
    std::printf("input      %zu faces\n", rep.input_faces);
    if (weighted)
      std::printf("weights    %s, lambda %g, alpha %.6g (%g-th percentile)\n", a.text.weights.c_str(), wo.lambda, ooc.alpha,
                  wo.alpha_percentile);
    else
      std::printf("weights    none (plain quadric error)\n");
    std::printf("tiles      %u (largest estimated at %.0f MiB, %u at a time; peak resident %.0f MiB of %.0f MiB)%s\n",
                ooc.tiles, ooc.tile_estimate / 1048576.0, ooc.groups_at_once, peak / 1048576.0,
                r.out_of_core.memory_limit / 1048576.0, shared_by().c_str());
    for (const StageTime& st : ooc.stages) std::printf("%-10s %8.3f s\n", st.name.c_str(), st.seconds);
    std::printf("output     %zu vertices, %zu faces (target %zu), %zu collapses\n", rep.output_vertices,
                rep.output_faces, rep.target_faces, rep.collapses);
    std::printf("error      %.4g%% of the bounding-box diagonal (largest collapse)\n", 100 * rep.error);
    std::printf("wrote      %s\n", printable(a.output).c_str());
  }
}

// --lod: the chain of levels, the saliency computed once; every file it wrote is named.
void print_lod(const Args& a, const meshsal::RequestResult& result) {
  using namespace meshsal;
  const bool one_file = result.lod_files.size() == 1 && result.lod.size() > 1;
  if (a.text.json) {
    std::vector<JsonObject> js;
    for (size_t i = 0; i < result.lod.size(); ++i) {
      const SimplifyReport& r = result.lod[i].report;
      js.push_back(JsonObject()
                       .count("level", i + 1)
                       .text("output", one_file ? result.lod_files[0] : result.lod_files[i])
                       .count("target_faces", r.target_faces)
                       .count("output_faces", r.output_faces)
                       .count("output_vertices", r.output_vertices)
                       .flag("reached", r.reached)
                       .flag("unchanged", r.unchanged)
                       .number("error_percent", 100 * r.error)
                       .number("seconds", r.seconds));
    }
    JsonObject().text("mesh", a.input).count("input_vertices", result.mesh.vertex_count())
        .count("input_faces", result.mesh.triangle_count()).text("weights", a.text.weights).objects("levels", js)
        .strings("outputs", result.outputs).number("seconds", result.seconds).print();
  } else if (!a.text.quiet) {
    std::printf("input      %zu vertices, %zu faces\n", result.mesh.vertex_count(), result.mesh.triangle_count());
    std::printf("weights    %s (saliency computed once, carried down the chain)\n", a.text.weights.c_str());
    for (size_t i = 0; i < result.lod.size(); ++i) {
      const SimplifyReport& r = result.lod[i].report;
      std::printf("LOD%zu       %zu faces (target %zu), %zu vertices, error %.4g%%%s\n", i + 1, r.output_faces,
                  r.target_faces, r.output_vertices, 100 * r.error,
                  one_file ? "" : printable(" -> " + result.lod_files[i]).c_str());
    }
    if (one_file) std::printf("wrote      %s (LOD0 = the input, MSFT_lod)\n", printable(result.lod_files[0]).c_str());
    else
      for (const std::string& f : result.outputs) std::printf("wrote      %s\n", printable(f).c_str());
  }
}

void print_simplified(const Args& a, const meshsal::Request& r, const meshsal::RequestResult& result, uint64_t peak) {
  using namespace meshsal;
  const SimplifyReport& rep = result.simplify;
  const Mesh& out = result.simplified;
  const bool weighted = r.weighting != Weighting::None && !rep.unchanged;
  const SaliencyWeightOptions& wo = r.weight_options;
  if (a.text.json) {
    const double diagonal = mesh_points_bbox(result.mesh, referenced_vertices(result.mesh)).diagonal();
    JsonObject j;
    j.text("mesh", a.input).text("output", a.output).count("input_vertices", result.mesh.vertex_count())
        .count("input_faces", rep.input_faces).count("output_vertices", rep.output_vertices)
        .count("output_faces", rep.output_faces).count("target_faces", rep.target_faces)
        .flag("unchanged", rep.unchanged).count("collapses", rep.collapses).flag("reached", rep.reached)
        .text("weights", a.text.weights).text("device", weighted && !result.weights_device.empty() ? result.weights_device : "cpu")
        // The error in model units and in % of the diagonal, as every command gives distances.
        .number("diagonal", diagonal).number("error", rep.error * diagonal)
        .number("error_percent", 100 * rep.error).number("weight_floor", weighted ? wo.floor : 0.0)
        .number("target_error", a.target_error / 100 * diagonal)
        .number("target_error_percent", a.target_error)
        .flag("lock_border", a.lock_border).count("attributes", out.attributes.size())
        .count("tiles", size_t(std::max(1u, r.simplify.tiles))).count("ranks", size_t(mpi_world().size))
        .count("threads_per_rank", resolve_threads(r.simplify.threads));
    if (weighted)
      j.number("lambda", wo.lambda).number("alpha", result.alpha).number("alpha_percentile", wo.alpha_percentile)
          .text("saliency_from", a.text.saliency_from).number("saliency_seconds", result.weights_seconds);
    j.strings("outputs", result.outputs).number("read_seconds", result.load_seconds)
        .number("simplify_seconds", rep.seconds).number("seconds", result.seconds)
        .count("peak_rss", size_t(peak)).print();
  } else if (!a.text.quiet) {
    std::printf("input      %zu vertices, %zu faces (read in %.3f s)\n", result.mesh.vertex_count(), rep.input_faces,
                result.load_seconds);
    if (weighted)
      std::printf("weights    %s%s, lambda %g, alpha %.6g (%g-th percentile), %.3f s\n", a.text.weights.c_str(),
                  a.text.saliency_from.empty() ? "" : printable(" from " + a.text.saliency_from).c_str(), wo.lambda,
                  result.alpha, wo.alpha_percentile, result.weights_seconds);
    else
      std::printf("weights    none (plain quadric error)\n");
    if (r.simplify.tiles > 1) std::printf("tiles      %u%s\n", r.simplify.tiles, shared_by().c_str());
    std::printf("output     %zu vertices, %zu faces (target %zu), %zu collapses in %.3f s\n", rep.output_vertices,
                rep.output_faces, rep.target_faces, rep.collapses, rep.seconds);
    std::printf("error      %.4g%% of the bounding-box diagonal (largest collapse)", 100 * rep.error);
    if (a.target_error > 0) std::printf(", target %g%%", a.target_error);
    std::printf("\n");
    if (!out.attributes.empty()) {
      std::string names;
      for (const VertexAttribute& at : out.attributes) names += " " + at.name;
      std::printf("attributes%s\n", printable(names).c_str());
    }
    for (const std::string& f : result.outputs) std::printf("wrote      %s\n", printable(f).c_str());
  }
}

int run(Args a) {
  using namespace meshsal;
  const bool rank0 = mpi_world().rank == 0;
  a.text.quiet = a.text.quiet || !rank0;  // one voice under mpirun: rank 0's
  Progress progress(!a.text.quiet && stderr_is_terminal());
  Request r = request_from(a.text, &progress);
  r.input = a.input;
  if (a.has_target) r.simplify.target_faces = size_t(a.target_faces);
  if (a.has_ratio) r.simplify.ratio = a.ratio;
  r.simplify.target_error = a.target_error / 100;
  r.simplify.lock_border = a.lock_border;
  r.simplify.tiles = unsigned(std::max(0LL, a.tiles));  // S in the same tiles: run_request's rule
  if (!a.lod.empty()) {
    r.lod = parse_lod_levels(a.lod);
    r.lod_output = a.output;
  } else {
    r.simplified_output = a.output;
  }
  // Under mpirun the ranks share the saliency's tiles and the passes' groups (by default
  // default_mpi_tiles of them); rank 0 writes and reports.
  MpiTileExchange exchange;
  if (mpi_world().active) {
    r.simplify.exchange = &exchange;
    r.saliency.exchange = &exchange;
    // (Out of core: at least that many, so every rank has groups even where the limit
    // would take fewer.)
    if (r.simplify.tiles == 0) r.simplify.tiles = default_mpi_tiles(mpi_world().size);
  }
  // After each rank read the input: one that cannot stops every rank alike.
  r.on_read = [&a] { begin_work(a); };
  const RequestResult result = run_request(r);
  progress.finish();
  const uint64_t peak = max_over_ranks(meshsal::peak_resident_bytes());
  if (!rank0) return 0;
  if (r.out_of_core.memory_limit > 0) print_out_of_core(a, r, result, peak);
  else if (!a.lod.empty()) print_lod(a, result);
  else print_simplified(a, r, result, peak);
  return 0;
}

RunFn setup(CLI::App& sub) {
  auto a = std::make_shared<Args>();
  sub.footer(
      "Simplify IN by Garland-Heckbert edge collapses to a face count. Every vertex quadric is\n"
      "first multiplied by W = lambda*Sm where the smoothed saliency Sm = G(S, 3 eps) reaches the\n"
      "alpha-percentile, else Sm (Lee et al. 2005, sec. 4). --weights balanced (the default):\n"
      "alpha at the 50th percentile, lambda 3; --weights saliency, the paper's recipe: alpha at\n"
      "the 30th, lambda 100 (on the bunny 3x the RMS and Hausdorff error of plain quadrics).\n"
      "Collapses that would make the mesh non-manifold, flip or fold a triangle are refused; a\n"
      "closed mesh only has even face counts, so an odd target ends one face above it (noted).\n"
      "Texture coordinates and normals (OBJ vt/vn) and other PLY vertex properties are carried to\n"
      "the output, interpolated along each collapsed edge; UV seams stay closed (seam vertices\n"
      "do not move and collapse only along the seam, both sides at once).\n"
      "A PLY output also gets the saliency S as `quality`, a glTF output (.glb, .gltf) as\n"
      "_SALIENCY and COLOR_0, with a glTF input's node transform and materials (unless\n"
      "--weights none).");
  sub.add_option("input", a->input, "Input mesh (.obj, .ply, .off, .stl, .gltf, .glb, optionally .gz)")->required();
  sub.add_option("-o,--output", a->output, "Output mesh (.obj with its .mtl, .ply, .glb, .gltf, .off or .stl)")->required();
  sub.add_option_function<long long>(
      "--target-faces", [a](long long n) { a->target_faces = n; a->has_target = true; },
      "Number of faces to keep")->check(whole_in(1, 4000000000LL));
  sub.add_option_function<double>(
      "--ratio", [a](double r) { a->ratio = r; a->has_ratio = true; },
      "Fraction of the faces to keep, in (0, 1]")->check(finite_in(0, 1, true));
  sub.add_option("--target-error", a->target_error,
                 "Error bound E in % of the bounding-box diagonal: stop where every further collapse would\n"
                 "move the surface more than that (RMS distance to the merged planes); alone, or with a face\n"
                 "target (whichever comes first). The error reached is reported")
      ->check(finite_in(0, 100, true));
  sub.add_flag("--lock-border", a->lock_border, "Keep the vertices of open borders exactly in place");
  sub.add_option("--lod", a->lod,
                 "Levels of detail in one run, e.g. 0.5,0.2,0.05 (ratios of the input's faces) or 20000,5000\n"
                 "(face counts): the saliency computed once, each level simplified from the one before.\n"
                 "OUT.glb/.gltf holds the input as LOD0 and every level (MSFT_lod); OUT.obj/.ply gives\n"
                 "OUT_lod1.obj, OUT_lod2.obj, ...")
      ->check(lod_list());
  sub.add_option("--tiles", a->tiles,
                 "Simplify by N cubic tiles along the longest axis (1 = the whole mesh at once): each tile alone\n"
                 "with its cut pinned, then strips along the cuts; no cracks, no new border; faces\n"
                 "at or just above the target (rounds with few output faces take fewer tiles). Takes\n"
                 "--target-faces or --ratio (not --target-error), not an OBJ split at UV seams")
      ->check(whole_in(1, 1024));
  add_memory_options(sub, a->text,
                     "Keep the peak resident memory under SIZE (e.g. 700M, 2G): the input (binary PLY is\n"
                     "streamed; other formats are read once and converted) goes to tiles on disk; the saliency\n"
                     "and then the tiled simplification (as --tiles, at least that many tiles) run a tile at a\n"
                     "time. Writes a binary PLY with positions and S; too small a limit is an error naming the\n"
                     "smallest workable one. CPU only.");
  add_weight_options(sub, a->text);
  add_saliency_from_option(sub, a->text);
  add_saliency_options(sub, a->text);
  add_output_flags(sub, a->text, "Print the summary as one JSON object on stdout (with \"outputs\": every file written)");
  return [a] { return run(*a); };
}

const bool registered = register_command(
    {"simplify", "Simplify a mesh, guided by saliency (or plain quadric error)", 20, setup, true});

}  // namespace
}  // namespace meshsal::cli
