// meshsal simplify IN -o OUT: Garland-Heckbert simplification, saliency-weighted by default.
#include <algorithm>
#include <cstdio>
#include <memory>

#include "command.h"
#include "json_string.h"
#include "core/mesh_points.h"
#include "core/timer.h"
#include "meshsal/meshsal.h"
#include "saliency/saliency.h"
#include "simplify/simplify.h"
#include "number_options.h"
#include "output_check.h"
#include "json_object.h"
#include "load_input.h"
#include "progress.h"
#include "saliency_output.h"
#include "interrupt.h"
#include "core/peak_memory.h"

namespace meshsal_cli {
namespace {

struct Args {
  std::string precision = "auto";  // --precision
  std::string method = "exact";    // --method
  std::string input, output, saliency_from, backend = "auto";
  std::string weights = meshsal::weighting_name(meshsal::kDefaultWeighting);  // --weights
  long long target_faces = 0;
  double ratio = 0;
  double lambda = 100, alpha_percentile = 30, weight_floor = meshsal::kDefaultWeightFloor, eps_frac = 0.003;
  double target_error = 0;  // --target-error, % of the bounding-box diagonal
  bool has_target = false, has_ratio = false, quiet = false, json = false, lock_border = false;
  bool lambda_given = false, alpha_given = false;  // override the --weights preset's
  unsigned threads = 0;
  long long tiles = 0;  // --tiles: 0 = not given (one piece)
  std::string memory_limit, temp_dir;  // --memory-limit, --temp-dir
  std::string lod;                     // --lod: ratios or face counts
};

// S from a saliency PLY, as `meshsal saliency` writes it for the same input. For an OBJ
// split at UV seams that is the saliency of its positions: the first vertices, the twins
// after them. A PLY's twins are vertices of the file: one value each.
std::vector<double> load_saliency_of_positions(const std::string& path, const meshsal::Mesh& mesh,
                                               bool ply_input) {
  const std::vector<uint32_t>& pv = mesh.position_vertex;
  if (pv.empty() || ply_input) return meshsal::load_saliency_ply(path, mesh);
  size_t positions = 0;
  while (positions < pv.size() && pv[positions] == positions) ++positions;
  meshsal::Mesh own;
  own.positions.assign(mesh.positions.begin(), mesh.positions.begin() + 3 * positions);
  for (int k = 0; k < 3; ++k) own.origin[k] = mesh.origin[k];
  if (!mesh.source_positions.empty())
    own.source_positions.assign(mesh.source_positions.begin(), mesh.source_positions.begin() + 3 * positions);
  own.triangles = mesh.triangles;
  for (uint32_t& v : own.triangles) v = pv[v];
  std::vector<double> s = meshsal::load_saliency_ply(path, own);
  s.resize(mesh.vertex_count());
  for (size_t i = positions; i < s.size(); ++i) s[i] = s[pv[i]];
  return s;
}

// The saliency the weights come from, as the options ask (progress on `progress`).
meshsal::SaliencyOptions saliency_options(const Args& a, Progress& progress) {
  meshsal::SaliencyOptions so;
  so.cancel = interrupt_flag();
  so.eps_frac = a.eps_frac;
  so.threads = a.threads;
  so.backend = parse_backend(a.backend);
  so.precision = meshsal::parse_precision(a.precision);
  so.method = meshsal::parse_method(a.method);
  // Tiled simplification takes its weights from tiled saliency (the same map, computed a
  // tile at a time).
  if (a.tiles > 1) so.tiles = unsigned(std::min<long long>(a.tiles, meshsal::kMaxTiles));
  so.progress = [&progress](const char* stage, double f) { progress.update(stage, f); };
  so.notice = [quiet = a.quiet](const std::string& line) {
    if (!quiet) std::fprintf(stderr, "%s\n", printable(line).c_str());
  };
  return so;
}

// --memory-limit: the library streams the file through tiles on disk (simplify_file).
int run_out_of_core(const Args& a, const meshsal::SimplifyOptions& opt, const meshsal::SaliencyWeightOptions& wo,
                    const meshsal::SaliencyOptions& so, Progress& progress) {
  using namespace meshsal;
  if (!a.saliency_from.empty()) throw UsageError("--memory-limit computes S itself: it does not take --saliency-from");
  if (a.target_error > 0) throw UsageError("--memory-limit takes --target-faces N or --ratio R, not --target-error");
  OutOfCoreOptions ooc;
  ooc.memory_limit = parse_memory_size(a.memory_limit);
  ooc.temp_dir = a.temp_dir;
  const meshsal::Timer t0;
  const OutOfCoreSimplifyReport r = simplify_file(a.input, a.output, opt, a.weights == "none" ? nullptr : &wo, so, ooc,
                                                  unsigned(std::max(1LL, a.tiles)));
  progress.finish();
  const SimplifyReport& rep = r.simplify;
  const uint64_t peak = meshsal::peak_resident_bytes();
  if (!rep.reached && !a.quiet) std::fprintf(stderr, "note: %s\n", printable(rep.note).c_str());
  if (a.json) {
    JsonObject j;
    j.text("mesh", a.input).text("output", a.output).count("input_vertices", size_t(r.saliency.vertices))
        .count("input_faces", rep.input_faces).count("output_vertices", rep.output_vertices)
        .count("output_faces", rep.output_faces).count("target_faces", rep.target_faces)
        .flag("unchanged", rep.unchanged).count("collapses", rep.collapses).flag("reached", rep.reached)
        .text("weights", a.weights).text("device", "cpu").number("error_percent", 100 * rep.error)
        .flag("lock_border", a.lock_border).count("tiles", r.tiles).count("saliency_tiles", r.saliency.tiles)
        .count("memory_limit", size_t(ooc.memory_limit)).count("tile_estimate", size_t(r.tile_estimate))
        .count("peak_rss", size_t(peak));
    if (a.weights != "none")
      j.number("lambda", wo.lambda).number("alpha", r.alpha).number("alpha_percentile", wo.alpha_percentile);
    j.number("seconds", t0.seconds()).print();
  } else if (!a.quiet) {
    std::printf("input      %zu faces\n", rep.input_faces);
    if (a.weights != "none")
      std::printf("weights    %s, lambda %g, alpha %.6g (%g-th percentile)\n", a.weights.c_str(), wo.lambda, r.alpha,
                  wo.alpha_percentile);
    else
      std::printf("weights    none (plain quadric error)\n");
    std::printf("tiles      %u (largest estimated at %.0f MiB; peak resident %.0f MiB of %.0f MiB)\n", r.tiles,
                r.tile_estimate / 1048576.0, peak / 1048576.0, ooc.memory_limit / 1048576.0);
    for (const StageTime& s : r.stages) std::printf("%-10s %8.3f s\n", s.name.c_str(), s.seconds);
    std::printf("output     %zu vertices, %zu faces (target %zu), %zu collapses\n", rep.output_vertices,
                rep.output_faces, rep.target_faces, rep.collapses);
    std::printf("error      %.4g%% of the bounding-box diagonal (largest collapse)\n", 100 * rep.error);
    std::printf("wrote      %s\n", printable(a.output).c_str());
  }
  return 0;
}

// --lod: the chain of levels (simplify_lod), the saliency computed once, written by
// write_lod (one glTF with every level, or OUT_lodI files).
int run_lod(const Args& a, const meshsal::SaliencyWeightOptions& wo, Progress& progress) {
  using namespace meshsal;
  const std::vector<SimplifyOptions> levels = parse_lod_levels(a.lod);
  const std::string format = mesh_output_format(a.output);
  const bool gltf = format == ".glb" || format == ".gltf";
  std::vector<OutputFile> outputs;
  if (gltf) outputs.push_back({a.output, "-o", {}});
  for (size_t i = 0; !gltf && i < levels.size(); ++i) outputs.push_back({lod_level_path(a.output, i + 1), "-o", {}});
  check_outputs(outputs, {a.input, a.saliency_from});
  const meshsal::Timer t0;
  progress.update("reading", 0.0);
  Mesh mesh = load_input(a.input, a.quiet, nullptr, true);
  SaliencyOptions so = saliency_options(a, progress);
  so.raw_maps = false;  // only S is used
  const bool weighted = a.weights != "none";
  std::vector<double> s;
  if (weighted) {
    progress.update("saliency", 0.0);
    s = a.saliency_from.empty() ? compute_saliency(mesh, so).saliency
                                : load_saliency_of_positions(a.saliency_from, mesh, mesh_extension(a.input) == ".ply");
  }
  progress.update("simplifying", 0.0);
  std::vector<SimplifyOptions> opts = levels;
  for (SimplifyOptions& o : opts) o.lock_border = a.lock_border, o.cancel = interrupt_flag();
  const std::vector<LodLevel> chain = simplify_lod(mesh, opts, weighted ? &wo : nullptr, so, weighted ? &s : nullptr);
  progress.update("writing", 0.0);
  write_lod(a.output, mesh, weighted ? &s : nullptr, chain);
  progress.finish();
  if (a.json) {
    std::vector<JsonObject> js;
    for (size_t i = 0; i < chain.size(); ++i) {
      const SimplifyReport& r = chain[i].report;
      js.push_back(JsonObject()
                       .count("level", i + 1)
                       .text("output", gltf ? a.output : lod_level_path(a.output, i + 1))
                       .count("target_faces", r.target_faces)
                       .count("output_faces", r.output_faces)
                       .count("output_vertices", r.output_vertices)
                       .flag("reached", r.reached)
                       .number("error_percent", 100 * r.error)
                       .number("seconds", r.seconds));
    }
    JsonObject().text("mesh", a.input).text("output", a.output).count("input_vertices", mesh.vertex_count())
        .count("input_faces", mesh.triangle_count()).text("weights", a.weights).objects("levels", js)
        .number("seconds", t0.seconds()).print();
  } else if (!a.quiet) {
    std::printf("input      %zu vertices, %zu faces\n", mesh.vertex_count(), mesh.triangle_count());
    std::printf("weights    %s (saliency computed once, carried down the chain)\n", a.weights.c_str());
    for (size_t i = 0; i < chain.size(); ++i) {
      const SimplifyReport& r = chain[i].report;
      std::printf("LOD%zu       %zu faces (target %zu), %zu vertices, error %.4g%%%s\n", i + 1, r.output_faces,
                  r.target_faces, r.output_vertices, 100 * r.error,
                  gltf ? "" : printable(" -> " + lod_level_path(a.output, i + 1)).c_str());
    }
    std::printf("wrote      %s\n", printable(gltf ? a.output + " (LOD0 = the input, MSFT_lod)" : a.output).c_str());
  }
  for (size_t i = 0; i < chain.size() && !a.quiet; ++i)
    if (!chain[i].report.reached || chain[i].report.unchanged)
      std::fprintf(stderr, "note: LOD%zu: %s\n", i + 1, printable(chain[i].report.note).c_str());
  return 0;
}

// The simplified mesh in the format its name gives; a glTF takes the saliency the
// simplifier carried (the `quality` attribute) as _SALIENCY and COLOR_0.
void write_simplified(const std::string& path, const meshsal::Mesh& mesh) {
  const std::string format = meshsal::mesh_output_format(path);
  if (format != ".glb" && format != ".gltf") return meshsal::write_mesh(path, mesh);
  meshsal::Mesh plain = mesh;
  const std::vector<double> s = meshsal::take_vertex_attribute(plain, "quality");
  meshsal::write_mesh(path, plain, s.empty() ? nullptr : &s);
}

int run(const Args& a) {
  using namespace meshsal;
  // Before any work: the output is a writable .obj/.ply/.glb/.gltf that is none of the inputs.
  check_outputs({{a.output, "-o", {".obj", ".ply", ".glb", ".gltf"}}}, {a.input, a.saliency_from});
  const bool obj = mesh_output_format(a.output) == ".obj";
  if (a.has_target && a.has_ratio) throw UsageError("give only one of --target-faces N and --ratio R");
  if (!a.lod.empty() && (a.has_target || a.has_ratio || a.target_error > 0))
    throw UsageError("--lod names every level: give it without --target-faces, --ratio or --target-error");
  if (!a.lod.empty() && (a.tiles > 1 || !a.memory_limit.empty()))
    throw UsageError("--lod runs in memory, in one piece: not with --tiles or --memory-limit");
  if (a.lod.empty() && !a.has_target && !a.has_ratio && a.target_error == 0)
    throw UsageError("give --target-faces N, --ratio R or --target-error E");
  if (a.weights != "saliency" && a.weights != "balanced" && a.weights != "none")
    throw UsageError("--weights must be 'saliency', 'balanced' or 'none', got '" + a.weights + "'");
  // The tiled path takes a face target only (simplify_mesh_tiled).
  if (a.tiles > 1 && a.target_error > 0) throw UsageError("--tiles takes --target-faces N or --ratio R, not --target-error");
  if (a.weights == "none" && !a.saliency_from.empty())
    throw UsageError("--saliency-from needs --weights saliency or balanced");
  // The named weighting's parameters, with --lambda / --alpha-percentile when given.
  SaliencyWeightOptions wo = weight_preset(parse_weighting(a.weights));
  if (a.lambda_given) wo.lambda = a.lambda;
  if (a.alpha_given) wo.alpha_percentile = a.alpha_percentile;
  wo.floor = a.weight_floor;

  Progress progress(!a.quiet && stderr_is_terminal());
  if (!a.lod.empty()) return run_lod(a, wo, progress);
  if (!a.memory_limit.empty()) {
    if (mesh_output_format(a.output) != ".ply") throw UsageError("--memory-limit writes a binary PLY: give -o OUT.ply");
    SimplifyOptions opt;
    opt.cancel = interrupt_flag();
    if (a.has_target) opt.target_faces = size_t(a.target_faces);
    else opt.ratio = a.ratio;
    opt.lock_border = a.lock_border;
    return run_out_of_core(a, opt, wo, saliency_options(a, progress), progress);
  }
  const meshsal::Timer t0;
  progress.update("reading", 0.0);
  // Attributes (OBJ vt/vn, PLY properties) are carried to the output.
  Mesh mesh = load_input(a.input, a.quiet, nullptr, true);
  const double t_load = t0.seconds();

  SimplifyOptions opt;
  opt.cancel = interrupt_flag();
  if (a.has_target) opt.target_faces = size_t(a.target_faces);
  else opt.ratio = a.ratio;
  opt.target_error = a.target_error / 100;
  opt.lock_border = a.lock_border;
  // A target at or above the face count keeps the mesh as it is (the library's rule), with
  // no saliency computed for it.
  if ((a.has_target || a.has_ratio) && simplify_keeps_mesh(opt, mesh.triangle_count())) {
    progress.update("writing", 0.0);
    write_simplified(a.output, mesh);
    progress.finish();
    if (const std::string note = mesh_output_note(a.output, mesh, false); !a.quiet && !note.empty())
      std::fprintf(stderr, "note: %s\n", printable(note).c_str());
    if (a.json)
      JsonObject()
          .text("mesh", a.input).text("output", a.output).count("input_vertices", mesh.vertex_count())
          .count("input_faces", mesh.triangle_count()).count("output_vertices", mesh.vertex_count())
          .count("output_faces", mesh.triangle_count()).count("target_faces", mesh.triangle_count())
          .flag("unchanged", true).count("collapses", 0).count("tiles", size_t(std::max(1LL, a.tiles)))
          .text("device", "cpu").number("seconds", t0.seconds()).print();
    if (!a.quiet) {
      std::fprintf(stderr, "note: the target (%zu faces) is at or above the mesh's %zu faces: wrote it unchanged\n",
                   a.has_target ? size_t(a.target_faces) : mesh.triangle_count(), mesh.triangle_count());
      if (!a.json) std::printf("wrote      %s\n", printable(a.output).c_str());
    }
    return 0;
  }
  // Check the target before spending time on saliency.
  resolve_target_faces(opt, mesh.triangle_count());

  std::vector<double> weights;
  bool told_precision = false;  // the saliency's notice already gave precision_warning
  double t_saliency = 0, alpha = 0;
  std::string device = "cpu";  // simplification runs on the CPU; computed saliency names its own
  if (a.weights != "none") {
    const meshsal::Timer ts;
    SaliencyOptions so = saliency_options(a, progress);
    so.notice = [&](const std::string& line) {
      told_precision |= line.find("float precision") != std::string::npos;
      if (!a.quiet) std::fprintf(stderr, "%s\n", printable(line).c_str());
    };
    std::vector<double> from_file;
    if (!a.saliency_from.empty()) {
      from_file = load_saliency_of_positions(a.saliency_from, mesh, mesh_extension(a.input) == ".ply");
      progress.update("smoothing saliency", 0.0);
    }
    // One call for every case; it names the device that computed S (seams too), and leaves
    // `device` at "cpu" when S comes from --saliency-from.
    SimplificationWeights w = simplification_weights(mesh, wo, so, a.saliency_from.empty() ? nullptr : &from_file);
    weights = std::move(w.weights);
    alpha = w.alpha;
    if (!w.device.empty()) device = w.device;
    t_saliency = ts.seconds();
    if (!obj) set_vertex_attribute(mesh, "quality", w.saliency);  // S goes to the output as `quality` (glTF: _SALIENCY)
  }

  progress.update("simplifying", 0.0);
  SimplifyReport rep;
  const std::vector<double>* w = weights.empty() ? nullptr : &weights;
  const Mesh out = a.tiles > 1 ? simplify_mesh_tiled(mesh, opt, unsigned(a.tiles), w, &rep) : simplify_mesh(mesh, opt, w, &rep);
  progress.update("writing", 0.0);
  write_simplified(a.output, out);
  progress.finish();
  if (const std::string note = mesh_output_note(a.output, out, false); !a.quiet && !note.empty())
    std::fprintf(stderr, "note: %s\n", printable(note).c_str());
  // With only an error bound there is no face target to miss.
  if (!rep.warning.empty() && !told_precision && !a.quiet && rep.note.find(rep.warning) == std::string::npos)
    std::fprintf(stderr, "warning: %s\n", printable(rep.warning).c_str());
  if (!rep.reached && !a.quiet && (a.has_target || a.has_ratio)) std::fprintf(stderr, "note: %s\n", printable(rep.note).c_str());
  if (a.json) {
    const double diagonal = mesh_points_bbox(mesh, referenced_vertices(mesh)).diagonal();
    JsonObject j;
    j.text("mesh", a.input).text("output", a.output).count("input_vertices", mesh.vertex_count())
        .count("input_faces", rep.input_faces).count("output_vertices", rep.output_vertices)
        .count("output_faces", rep.output_faces).count("target_faces", rep.target_faces)
        .flag("unchanged", false).count("collapses", rep.collapses).flag("reached", rep.reached)
        .text("weights", a.weights).text("device", device)
        // The error in model units and in % of the diagonal, as every command gives distances.
        .number("diagonal", diagonal).number("error", rep.error * diagonal)
        .number("error_percent", 100 * rep.error).number("weight_floor", weights.empty() ? 0.0 : wo.floor)
        .number("target_error", a.target_error / 100 * diagonal)
        .number("target_error_percent", a.target_error)
        .flag("lock_border", a.lock_border).count("attributes", out.attributes.size())
        .count("tiles", size_t(std::max(1LL, a.tiles)));
    if (!weights.empty())
      j.number("lambda", wo.lambda).number("alpha", alpha).number("alpha_percentile", wo.alpha_percentile)
          .text("saliency_from", a.saliency_from).number("saliency_seconds", t_saliency);
    j.number("read_seconds", t_load).number("simplify_seconds", rep.seconds).number("seconds", t0.seconds())
        .count("peak_rss", size_t(meshsal::peak_resident_bytes())).print();
  } else if (!a.quiet) {
    std::printf("input      %zu vertices, %zu faces (read in %.3f s)\n", mesh.vertex_count(),
                rep.input_faces, t_load);
    if (!weights.empty())
      std::printf("weights    %s%s, lambda %g, alpha %.6g (%g-th percentile), %.3f s\n", a.weights.c_str(),
                  a.saliency_from.empty() ? "" : printable(" from " + a.saliency_from).c_str(), wo.lambda,
                  alpha, wo.alpha_percentile, t_saliency);
    else
      std::printf("weights    none (plain quadric error)\n");
    std::printf("output     %zu vertices, %zu faces (target %zu), %zu collapses in %.3f s\n",
                rep.output_vertices, rep.output_faces, rep.target_faces, rep.collapses, rep.seconds);
    std::printf("error      %.4g%% of the bounding-box diagonal (largest collapse)", 100 * rep.error);
    if (a.target_error > 0) std::printf(", target %g%%", a.target_error);
    std::printf("\n");
    if (!out.attributes.empty()) {
      std::string names;
      for (const VertexAttribute& at : out.attributes) names += " " + at.name;
      std::printf("attributes%s\n", printable(names).c_str());
    }
    std::printf("wrote      %s\n", printable(a.output).c_str());
  }
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
  sub.add_option("-o,--output", a->output, "Output mesh (.obj, .ply, .glb or .gltf)")->required();
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
                 "at or just above the target (more with tiles only a few output triangles wide). Takes\n"
                 "--target-faces or --ratio (not --target-error), not an OBJ split at UV seams")
      ->check(whole_in(1, 1024));
  sub.add_option("--memory-limit", a->memory_limit,
                 "Keep the peak resident memory under SIZE (e.g. 700M, 2G): the input (binary PLY is\n"
                 "streamed; other formats are read once and converted) goes to tiles on disk; the saliency\n"
                 "and then the tiled simplification (as --tiles, at least that many tiles) run a tile at a\n"
                 "time. Writes a binary PLY with positions and S; too small a limit is an error naming the\n"
                 "smallest workable one. CPU only. " + std::string(kSizeSyntax))
      ->check(memory_size());
  add_temp_dir_option(sub, &a->temp_dir);
  sub.add_option("--weights", a->weights,
                 "balanced (the paper's curve with alpha at the 50th percentile and lambda 3: salient "
                 "detail at little cost elsewhere), saliency (the paper's recipe, lambda 100 above the "
                 "30th percentile: more salient detail, RMS and Hausdorff error up to ~3x plain's) or "
                 "none (plain quadric error)")
      ->capture_default_str();
  CLI::Option* lambda = sub.add_option("--lambda", a->lambda, "Amplification of the salient vertices "
                                       "(default: the --weights preset's: 3 for balanced, 100 for saliency)")
      ->check(finite_in(0, 1e6));
  CLI::Option* alpha = sub.add_option("--alpha-percentile", a->alpha_percentile,
                 "Percentile of Sm above which vertices are amplified (default: the --weights preset's: 50 "
                 "for balanced, 30 for saliency)")->check(finite_in(0, 100));
  sub.add_option("--saliency-from", a->saliency_from,
                 "Reuse S from this saliency PLY (`quality` property) instead of computing it");
  sub.add_option("--weight-floor", a->weight_floor,
                 "Not in the paper: raise W to at least this fraction of its mean W, so that no collapse is free\n"
                 "(flat regions have Sm = 0; 0 = the paper's literal rule, which can erase them)")
      ->capture_default_str()->check(finite_in(0, 100));
  sub.add_option("--eps-frac", a->eps_frac, "eps as a fraction of the bounding-box diagonal")
      ->capture_default_str()->check(finite_in(0, meshsal::kMaxEpsFrac, true));
  sub.add_option("--backend", a->backend, "Saliency backend: auto, cpu or gpu")->capture_default_str();
  add_precision_option(sub, &a->precision);
  add_method_option(sub, &a->method);
  add_threads_option(sub, a->threads, "CPU threads for saliency (0 = all cores)");
  sub.add_flag("-q,--quiet", a->quiet, "Print nothing on success (no notes either)");
  sub.add_flag("--json", a->json, "Print the summary as one JSON object on stdout");
  return [a, lambda, alpha] {
    a->lambda_given = lambda->count() > 0;
    a->alpha_given = alpha->count() > 0;
    return run(*a);
  };
}

const bool registered = register_command(
    {"simplify", "Simplify a mesh, guided by saliency (or plain quadric error)", 20, setup});

}  // namespace
}  // namespace meshsal_cli
