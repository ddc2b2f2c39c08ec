// meshsal bench: time each saliency stage on real meshes, in the style of the paper's Table 1.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <sys/resource.h>
#include <unistd.h>

#include "cmd_bench_simplify.h"
#include "command.h"
#include "load_input.h"
#include "json_string.h"
#include "core/peak_memory.h"
#include "core/timer.h"
#include "json_object.h"
#include "cli/data_dir.h"
#include "meshsal/meshsal.h"
#include "number_options.h"
#include "core/mesh_points.h"
#include "cli/subdivide.h"
#include "saliency/gaussian_filter_fast.h"
#include "saliency/method_error.h"
#include "saliency/saliency.h"
#include "saliency_output.h"
#include "interrupt.h"
#if MESHSAL_WITH_VULKAN
#include "gpu/gpu_saliency.h"
#include "gpu/vk_context.h"
#endif

namespace meshsal::cli {
namespace {

struct Args {
  std::vector<std::string> meshes;
  std::string data_dir;
  bool json = false;
  bool quiet = false;  // -q: no progress line
  bool simplify = false;
  std::string plot, sweep = "short";  // --simplify only (cmd_bench_simplify.h)
  unsigned threads = 0;
  int repeat = 3;
  std::string method = "exact";  // fast: also the error against exact, per mesh
  std::string backend;           // cpu or gpu; empty: exact times every backend, fast the CPU
                                 // (read once by run() into an optional Backend)
  int subdivide = 0;             // midpoint subdivisions of each mesh, in memory
  std::string write_mesh;        // --write-mesh: write the (subdivided) mesh there and stop
};

// With --method fast the exact reference runs once per mesh unless its estimated pair count
// passes this (~60 s on 2 cores); then its time is estimated from the pairs instead.
constexpr double kExactReferencePairLimit = 2e10;
constexpr double kExactPairsPerSecond = 3.3e8;  // measured: 2 cores, igea_134k (README)

struct Row {
  std::string path;  // the mesh file as given (JSON "mesh")
  std::string model, device;
  std::string precision;  // of the sweep: "mixed" or "double"
  size_t vertices = 0;
  double read = 0;
  meshsal::SaliencyResult best;  // the fastest of the repeats
  double total = 0;
  meshsal::Method method = meshsal::Method::Exact;
  // --method fast: the exact reference (time, pairs) and the error against it.
  bool has_reference = false;
  double exact_total = 0, exact_pairs = 0;  // pairs estimated when there is no reference
  // --method fast: Sm = G(S, 3 eps) from a given S (simplify --saliency-from), with the fast
  // method's averages (smooth_saliency follows the method) and, with the reference, exact.
  double smooth_fast = 0, smooth_exact = 0;
  meshsal::MethodError error;
  double peak_rss = 0;  // bytes, after this row
};

// Each backend the table has a row for: the CPU path and every Vulkan device with compute,
// once per sweep precision; only `only`'s when given (--backend).
std::vector<meshsal::SaliencyOptions> bench_backends(const Args& a, std::optional<meshsal::Backend> only) {
  meshsal::SaliencyOptions cpu;
  cpu.cancel = interrupt_flag();
  cpu.backend = meshsal::Backend::Cpu;
  cpu.threads = a.threads;
  std::vector<meshsal::SaliencyOptions> out;
  if (only != meshsal::Backend::Gpu) out.push_back(cpu);
  if (only == meshsal::Backend::Cpu) return out;
  try {
    for (const auto& d : meshsal::list_devices()) {
      if (!d.has_compute) continue;
      meshsal::SaliencyOptions gpu = cpu;
      gpu.backend = meshsal::Backend::Gpu;
      gpu.device = d.index;
      for (auto precision : {meshsal::Precision::Mixed, meshsal::Precision::Double}) {  // both, explicitly
        gpu.precision = precision;
        out.push_back(gpu);
      }
    }
  } catch (const meshsal::Error& e) {
    if (only == meshsal::Backend::Gpu) throw;
    std::fprintf(stderr, "no Vulkan rows: %s\n", printable(e.what()).c_str());
  }
  if (out.empty()) throw meshsal::Error("bench --backend gpu: no Vulkan device with compute");
  return out;
}

Row bench_one(const std::string& model, const meshsal::Mesh& mesh, double read,
              const meshsal::SaliencyOptions& opt, int repeat) {
  Row row;
  row.model = model;
  row.read = read;
  row.vertices = mesh.vertex_count();
  // A Vulkan device is opened once for all repeats, so the driver's first compile of each
  // pipeline is paid once, as in a long-running program.
#if MESHSAL_WITH_VULKAN
  std::unique_ptr<meshsal::vk::Context> ctx;
  if (opt.backend == meshsal::Backend::Gpu) ctx = std::make_unique<meshsal::vk::Context>(opt.device);
#endif
  for (int i = 0; i < repeat; ++i) {
#if MESHSAL_WITH_VULKAN
    meshsal::SaliencyResult r = ctx ? meshsal::compute_saliency_gpu(*ctx, mesh, opt)
                                    : meshsal::compute_saliency(mesh, opt);
#else
    meshsal::SaliencyResult r = meshsal::compute_saliency(mesh, opt);
#endif
    double total = 0;
    for (const auto& s : r.stages) total += s.seconds;
    if (i == 0 || total < row.total) row.best = std::move(r), row.total = total;
  }
  row.device = row.best.backend_name;
  row.method = row.best.method;
  row.peak_rss = double(meshsal::peak_resident_bytes());
  row.precision = opt.backend == meshsal::Backend::Cpu ? "double"
                  : row.best.mixed_precision           ? "mixed"
                                                       : "double";
  return row;
}

// --method fast: the fast CPU row, then the exact reference once (or its estimated time when
// its pair count passes kExactReferencePairLimit) and the error of fast against it.
Row bench_fast(const std::string& model, const meshsal::Mesh& mesh, double read, const Args& a,
               std::optional<meshsal::Backend> only) {
  meshsal::SaliencyOptions opt;
  opt.cancel = interrupt_flag();
  opt.backend = only.value_or(meshsal::Backend::Cpu);
  opt.threads = a.threads;
  opt.method = meshsal::Method::Fast;
  // Whether the exact reference will run (then the raw maps are compared): without it the
  // fast run keeps no raw maps, as `meshsal saliency` without --dump-scales.
  double exact_pairs = 0;
  {
    const std::vector<uint8_t> is_point = meshsal::referenced_vertices(mesh);
    const double eps = meshsal::scale_unit(mesh, is_point, opt.eps_frac);
    const double largest = *std::max_element(opt.scales.begin(), opt.scales.end());
    exact_pairs = meshsal::estimate_sweep_pairs(mesh, is_point, 4 * largest * eps);
  }
  opt.raw_maps = exact_pairs <= kExactReferencePairLimit;
  Row row = bench_one(model, mesh, read, opt, a.repeat);
  row.exact_pairs = exact_pairs;
  opt.backend = meshsal::Backend::Cpu;  // the exact reference runs on the CPU path
  {
    const meshsal::Timer t;
    meshsal::smooth_saliency(mesh, row.best.saliency, opt);
    row.smooth_fast = t.seconds();
  }
  if (!opt.raw_maps) {
    row.exact_total = row.exact_pairs / kExactPairsPerSecond;
    return row;
  }
  opt.method = meshsal::Method::Exact;
  Row exact = bench_one(model, mesh, read, opt, 1);
  row.has_reference = true;
  row.exact_total = exact.total;
  {
    const meshsal::Timer t;
    meshsal::smooth_saliency(mesh, row.best.saliency, opt);  // opt.method is Exact now
    row.smooth_exact = t.seconds();
  }
  row.exact_pairs = double(exact.best.pairs);
  row.error = meshsal::method_error(exact.best, row.best);
  return row;
}

double stage(const Row& row, const char* name) {
  for (const auto& s : row.best.stages)
    if (s.name == name) return s.seconds;
  return 0.0;
}

void print_table(const std::vector<Row>& rows) {
  std::printf("%-24s %9s  %-22s %-6s %-5s %9s %9s %9s %9s %9s %9s %10s %10s %8s\n", "model", "vertices",
              "device", "prec", "meth", "curvature", "sweep", "c-s", "suppress", "other", "total", "pairs", "pairs/s", "recheck");
  for (const Row& r : rows) {
    const double listed = stage(r, "curvature") + stage(r, "gaussian sweep") +
                          stage(r, "center-surround") + stage(r, "suppression");
    std::printf("%-24s %9zu  %-22.22s %-6s %-5s %8.3fs %8.3fs %8.3fs %8.3fs %8.3fs %8.3fs %10.3g %10.3g %8llu\n",
                r.model.c_str(), r.vertices, r.device.c_str(), r.precision.c_str(), meshsal::method_name(r.method), stage(r, "curvature"),
                stage(r, "gaussian sweep"), stage(r, "center-surround"), stage(r, "suppression"),
                std::max(0.0, r.total - listed), r.total, double(r.best.pairs),
                r.total > 0 ? r.best.pairs / r.total : 0.0, (unsigned long long)r.best.rechecked);
  }
  bool any_fast = false;
  for (const Row& r : rows) any_fast |= r.method == meshsal::Method::Fast;
  if (any_fast) {
    std::printf("\n%-24s %9s %10s %10s %8s %10s %9s %9s %9s %9s %8s %9s %9s\n", "model", "vertices", "fast",
                "exact", "speed-up", "exact pairs", "corr", "top30", "raw mean", "raw max", "peak B/v", "Sm fast",
                "Sm exact");
    for (const Row& r : rows) {
      if (r.method != meshsal::Method::Fast) continue;
      double mean = 0, worst = 0;
      for (double x : r.error.raw_mean) mean = std::max(mean, x);
      for (double x : r.error.raw_max) worst = std::max(worst, x);
      if (r.has_reference)
        std::printf("%-24s %9zu %9.3fs %9.3fs %8.1f %10.3g %9.6f %9.4f %9.2e %9.2e %8.0f %8.3fs %8.3fs\n",
                    r.model.c_str(), r.vertices, r.total, r.exact_total, r.exact_total / r.total, r.exact_pairs,
                    r.error.correlation, r.error.top30_overlap, mean, worst, r.peak_rss / r.vertices, r.smooth_fast,
                    r.smooth_exact);
      else
        std::printf("%-24s %9zu %9.3fs %8.0fs* %8.0f %10.3g %9s %9s %9s %9s %8.0f %8.3fs %9s\n", r.model.c_str(),
                    r.vertices, r.total, r.exact_total, r.exact_total / r.total, r.exact_pairs, "-", "-",
                    "-", "-", r.peak_rss / r.vertices, r.smooth_fast, "-");
    }
    std::printf("(fast against exact on the same mesh, exact on the CPU path: corr = Pearson correlation of the final\n"
                " saliency, top30 = share of the exact top-30%% vertices in the fast top 30%%, raw mean/max =\n"
                " the worst map's mean and max |fast - exact| / map maximum (per map in --json); * = exact\n"
                " not run, time estimated from its pair count at %.2g pairs/s; peak B/v = peak resident\n"
                " memory of the process so far per vertex; Sm = smoothing a given S, as simplify\n"
                " --saliency-from does, with each method's averages)\n", kExactPairsPerSecond);
  }
  // Each stage's time and peak resident memory (the process's, the mesh included).
  std::printf("\n%-24s %-22s %-18s %9s %10s %9s\n", "model", "device", "stage", "seconds", "peak MB", "peak B/v");
  for (const Row& r : rows)
    for (const auto& st : r.best.stages) {
      if (st.peak_bytes == 0) {  // not measured (the Vulkan path's stages): no figure, not 0
        std::printf("%-24s %-22.22s %-18s %8.3fs %10s %9s\n", r.model.c_str(), r.device.c_str(), st.name.c_str(),
                    st.seconds, "-", "-");
        continue;
      }
      std::printf("%-24s %-22.22s %-18s %8.3fs %10.1f %9.1f\n", r.model.c_str(), r.device.c_str(), st.name.c_str(),
                  st.seconds, double(st.peak_bytes) / 1e6, r.vertices ? double(st.peak_bytes) / double(r.vertices) : 0.0);
    }
  std::printf("(per stage: its time and the process's peak resident memory while it ran, the mesh and\n"
              " what the heap kept from earlier stages included (meshsal keeps freed memory for reuse, so\n"
              " a stage's peak is at least what the process held when it began); the CPU fast method\n"
              " runs center-surround and suppression scale by scale inside the sweep: their peak is the\n"
              " sweep's; '-': not measured, as on Vulkan devices)\n");
  std::printf("(saliency only, file reading excluded; best of the repeats; on Vulkan devices the\n"
              " center-surround maps come out of the sweep, and `other` is upload, grid, download and,\n"
              " in mixed precision, the double recheck of near ties (and a device's first run its\n"
              " fp64 probe); prec: the sweep's arithmetic; recheck: points swept again in double)\n");
}

// One JSON object, as every command's --json: a row per mesh and device under "rows", each
// with its "mesh" (the file as given), "device" and "seconds" (the saliency total).
void print_json(const std::vector<Row>& rows, const Args& a, double seconds) {
  std::vector<JsonObject> items;
  for (const Row& r : rows) {
    JsonObject stages;
    JsonObject stage_peaks;
    for (const auto& st : r.best.stages) {
      stages.number(json_key(st.name), st.seconds);
      if (st.peak_bytes) stage_peaks.count(json_key(st.name), st.peak_bytes);  // measured ones only
    }
    JsonObject j;
    j.text("mesh", r.path).text("name", r.model).count("subdivisions", uint64_t(a.subdivide))
        .count("vertices", r.vertices).text("device", r.device).text("precision", r.precision)
        .text("method", meshsal::method_name(r.method)).number("read_seconds", r.read).number("seconds", r.total).object("stages", stages)
        .object("stage_peak_bytes", stage_peaks)
        .count("pairs", r.best.pairs).number("pairs_per_second", r.total > 0 ? r.best.pairs / r.total : 0.0)
        .count("rechecked", r.best.rechecked).count("peak_rss_bytes", uint64_t(r.peak_rss));
    if (r.method == meshsal::Method::Fast) {
      j.flag("exact_measured", r.has_reference).number("exact_seconds", r.exact_total).number("exact_pairs", r.exact_pairs);
      j.number("smooth_fast_seconds", r.smooth_fast);
      if (r.has_reference) j.number("smooth_exact_seconds", r.smooth_exact);
      if (r.has_reference)
        j.number("correlation", r.error.correlation).number("top30_overlap", r.error.top30_overlap)
            .numbers("raw_mean_rel", r.error.raw_mean).numbers("raw_max_rel", r.error.raw_max);
    }
    items.push_back(j);
  }
  JsonObject out;
  out.text("method", a.method).count("repeat", uint64_t(a.repeat)).count("threads", a.threads)
      .objects("rows", items).number("seconds", seconds).print();
}

int run(const Args& a) {
  std::vector<std::string> paths = a.meshes;
  const std::string dir = a.data_dir.empty() ? meshsal::benchmark_data_dir() : a.data_dir;
  if (a.simplify) return run_simplify_benchmark({a.meshes, dir, a.json, a.repeat, a.threads, a.plot, parse_sweep(a.sweep)});
  if (paths.empty()) {
    for (const char* name : {"bunny_36k.obj", "armadillo_43k.obj", "dragon_50k.ply", "igea_134k.ply.gz"}) {
      std::string p = dir + "/" + name;
      if (std::filesystem::exists(p))
        paths.push_back(p);
      else
        std::fprintf(stderr, "skipped %s: not found (give meshes as arguments or --data-dir)\n", printable(p).c_str());
    }
    if (paths.empty()) throw meshsal::Error("no benchmark meshes found in '" + dir + "'");
  }
  const meshsal::Method method = meshsal::parse_method(a.method);
  if (method == meshsal::Method::Auto) throw meshsal::Error("bench: --method must be exact or fast");
  std::optional<meshsal::Backend> only;  // --backend: cpu or gpu (checked by its option)
  if (!a.backend.empty()) only = meshsal::parse_backend(a.backend);
  std::vector<Row> rows;
  meshsal::set_stage_peaks(true);  // each stage's peak memory in the table and --json
  const meshsal::Timer wall;
  for (const std::string& p : paths) {
    const meshsal::Timer t0;
    meshsal::Mesh mesh = meshsal::load_mesh(p, load_options());
    std::string model = std::filesystem::path(p).filename().string();
    for (int k = 0; k < a.subdivide; ++k) mesh = meshsal::subdivide_midpoint(mesh);
    if (a.subdivide) model += " /" + std::to_string(a.subdivide);
    if (!a.write_mesh.empty()) {
      // The input of the tiles benchmark (tools/bench_tiles.sh): a mesh larger than the
      // data has, as a binary PLY.
      if (paths.size() != 1) throw UsageError("bench --write-mesh takes one mesh");
      meshsal::write_ply(a.write_mesh, mesh, {});
      std::printf("wrote %s: %zu vertices, %zu triangles\n", printable(a.write_mesh).c_str(), mesh.vertex_count(),
                  mesh.triangle_count());
      return 0;
    }
    const double read = t0.seconds();
    if (method == meshsal::Method::Fast) {
      rows.push_back(bench_fast(model, mesh, read, a, only));
      rows.back().path = p;
      continue;
    }
    for (const auto& opt : bench_backends(a, only)) {
      if (!a.json && !a.quiet && isatty(fileno(stderr))) std::fprintf(stderr, "  %s ...\r", printable(p).c_str());
      try {
        rows.push_back(bench_one(model, mesh, read, opt, a.repeat));
        rows.back().path = p;
      } catch (const meshsal::Error& e) {
        if (opt.backend == meshsal::Backend::Cpu) throw;
        std::fprintf(stderr, "skipped %s on Vulkan device %d: %s\n", printable(p).c_str(), opt.device,
                     printable(e.what()).c_str());
      }
    }
  }
  if (a.json)
    print_json(rows, a, wall.seconds());
  else
    print_table(rows);
  return 0;
}

RunFn setup(CLI::App& sub) {
  auto a = std::make_shared<Args>();
  sub.footer(
      "Time every saliency stage (file reading excluded) and report neighbour pairs per second,\n"
      "for the CPU path and each Vulkan device. Without MESHES it uses bunny_36k, armadillo_43k,\n"
      "dragon_50k and igea_134k from ../shared/data/meshes (or $MESHSAL_DATA).");
  sub.add_option("meshes", a->meshes, "Mesh files to time");
  sub.add_option("--data-dir", a->data_dir, "Folder of the default benchmark meshes");
  sub.add_flag("--json", a->json, "Print one JSON object (a row per mesh and device under \"rows\") instead of the table");
  // Accepted as every command takes it: the figures are the command's result.
  sub.add_flag("-q,--quiet", a->quiet, "No progress line on stderr (the figures are printed, and what was skipped)");
  sub.add_flag("--simplify", a->simplify,
               "Benchmark simplification instead (plain, saliency, balanced, meshoptimizer, and a sweep "
               "of the weighting) at 1% and 5% of the faces of armadillo_43k, dragon_50k, igea_134k, lucy_50k");
  sub.add_option("--plot", a->plot, "With --simplify: PNG of salient against RMS error, per model and ratio");
  sub.add_option("--sweep", a->sweep, "With --simplify: weighting parameters to sweep: short, wide or none")
      ->check(CLI::IsMember({"short", "wide", "none"}))->capture_default_str();
  add_threads_option(sub, a->threads, "CPU threads (0 = all cores)");
  sub.add_option("--method", a->method,
                 "exact, or fast: time the fast method (on --backend) and report its error "
                 "against exact (correlation, top-30% overlap, raw-map errors) and peak memory")
      ->check(CLI::IsMember({"exact", "fast"}))->capture_default_str();
  sub.add_option("--backend", a->backend,
                 "cpu or gpu. Exact: only the CPU path's rows, or only the Vulkan devices' "
                 "(default: both). Fast: where the fast rows run (default cpu; gpu = the first "
                 "Vulkan device, lavapipe included; the exact reference stays on the CPU path)")
      ->check(CLI::IsMember({"cpu", "gpu"}));
  sub.add_option("--subdivide", a->subdivide,
                 "Midpoint-subdivide each mesh N times in memory first (4x the triangles each)")
      ->capture_default_str()->check(whole_in(0, 3));
  sub.add_option("--write-mesh", a->write_mesh,
                 "Write the mesh (after --subdivide) as binary PLY to this path and stop: the "
                 "large input of tools/bench_tiles.sh");
  sub.add_option("--repeat", a->repeat, "Runs per mesh and device; the fastest is reported")
      ->capture_default_str()->check(whole_in(1, 1000));
  return [a] { return run(*a); };
}

const bool registered = register_command({"bench", "Benchmark saliency stages on real meshes", 40, setup});

}  // namespace
}  // namespace meshsal::cli
