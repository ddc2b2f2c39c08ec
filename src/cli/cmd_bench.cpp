// meshsal bench: time each saliency stage on real meshes, in the style of the paper's Table 1.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <unistd.h>

#include "command.h"
#include "json_string.h"
#include "cli/data_dir.h"
#include "meshsal/meshsal.h"
#include "number_options.h"
#include "saliency/saliency.h"
#if MESHSAL_WITH_VULKAN
#include "gpu/gpu_saliency.h"
#include "gpu/vk_context.h"
#endif

namespace meshsal_cli {
namespace {

struct Args {
  std::vector<std::string> meshes;
  std::string data_dir;
  bool json = false;
  bool simplify = false;
  unsigned threads = 0;
  int repeat = 3;
};

// `--simplify` runs tools/bench_simplify (built beside meshsal): only that program links
// meshoptimizer, the baseline it compares against.
int exec_simplify_benchmark(const Args& a, const std::string& data_dir) {
  std::error_code ec;
  std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  const std::string tool = (exe.parent_path() / "bench_simplify").string();
  if (ec || !std::filesystem::exists(tool))
    throw meshsal::Error("bench_simplify not found beside meshsal (build the tools target)");
  std::vector<std::string> args{tool};
  args.insert(args.end(), a.meshes.begin(), a.meshes.end());
  args.insert(args.end(), {"--data-dir", data_dir, "--repeat", std::to_string(a.repeat),
                           "--threads", std::to_string(a.threads)});
  if (a.json) args.push_back("--json");
  std::vector<char*> argv;
  for (std::string& s : args) argv.push_back(s.data());
  argv.push_back(nullptr);
  std::fflush(stdout);
  execv(tool.c_str(), argv.data());
  throw meshsal::Error("cannot run " + tool);
}

struct Row {
  std::string model, device;
  std::string precision;  // of the sweep: "mixed" or "double"
  size_t vertices = 0;
  double read = 0;
  meshsal::SaliencyResult best;  // the fastest of the repeats
  double total = 0;
};

// Each backend the table has a row for: the CPU path and every Vulkan device with compute,
// once per sweep precision.
std::vector<meshsal::SaliencyOptions> bench_backends(const Args& a) {
  meshsal::SaliencyOptions cpu;
  cpu.backend = meshsal::Backend::Cpu;
  cpu.threads = a.threads;
  std::vector<meshsal::SaliencyOptions> out{cpu};
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
    std::fprintf(stderr, "no Vulkan rows: %s\n", e.what());
  }
  return out;
}

Row bench_one(const std::string& path, const meshsal::SaliencyOptions& opt, int repeat) {
  using clock = std::chrono::steady_clock;
  Row row;
  row.model = std::filesystem::path(path).filename().string();
  auto t0 = clock::now();
  meshsal::Mesh mesh = meshsal::load_mesh(path);
  row.read = std::chrono::duration<double>(clock::now() - t0).count();
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
  row.precision = opt.backend == meshsal::Backend::Cpu ? "double"
                  : row.best.mixed_precision           ? "mixed"
                                                       : "double";
  return row;
}

double stage(const Row& row, const char* name) {
  for (const auto& s : row.best.stages)
    if (s.name == name) return s.seconds;
  return 0.0;
}

void print_table(const std::vector<Row>& rows) {
  std::printf("%-24s %9s  %-22s %-6s %9s %9s %9s %9s %9s %9s %10s %10s %8s\n", "model", "vertices",
              "device", "prec", "curvature", "sweep", "c-s", "suppress", "other", "total", "pairs", "pairs/s", "recheck");
  for (const Row& r : rows) {
    const double listed = stage(r, "curvature") + stage(r, "gaussian sweep") +
                          stage(r, "center-surround") + stage(r, "suppression");
    std::printf("%-24s %9zu  %-22.22s %-6s %8.3fs %8.3fs %8.3fs %8.3fs %8.3fs %8.3fs %10.3g %10.3g %8llu\n",
                r.model.c_str(), r.vertices, r.device.c_str(), r.precision.c_str(), stage(r, "curvature"),
                stage(r, "gaussian sweep"), stage(r, "center-surround"), stage(r, "suppression"),
                std::max(0.0, r.total - listed), r.total, double(r.best.pairs),
                r.total > 0 ? r.best.pairs / r.total : 0.0, (unsigned long long)r.best.rechecked);
  }
  std::printf("(saliency only, file reading excluded; best of the repeats; on Vulkan devices the\n"
              " center-surround maps come out of the sweep, and `other` is upload, grid, download and,\n"
              " in mixed precision, the double recheck of near ties; prec: the sweep's arithmetic;\n"
              " recheck: points swept again in double)\n");
}

void print_json(const std::vector<Row>& rows) {
  std::printf("[\n");
  for (size_t i = 0; i < rows.size(); ++i) {
    const Row& r = rows[i];
    std::printf("  {\"model\": %s, \"vertices\": %zu, \"device\": %s, \"precision\": %s, "
                "\"read_s\": %.6f, \"stages\": {",
                json_string(r.model).c_str(), r.vertices, json_string(r.device).c_str(),
                json_string(r.precision).c_str(), r.read);
    for (size_t s = 0; s < r.best.stages.size(); ++s)
      std::printf("%s%s: %.6f", s ? ", " : "", json_string(r.best.stages[s].name).c_str(),
                  r.best.stages[s].seconds);
    std::printf("}, \"total_s\": %.6f, \"pairs\": %llu, \"pairs_per_s\": %.6g, \"rechecked\": %llu}%s\n",
                r.total, (unsigned long long)r.best.pairs, r.total > 0 ? r.best.pairs / r.total : 0.0,
                (unsigned long long)r.best.rechecked,
                i + 1 < rows.size() ? "," : "");
  }
  std::printf("]\n");
}

int run(const Args& a) {
  std::vector<std::string> paths = a.meshes;
  const std::string dir = a.data_dir.empty() ? meshsal::benchmark_data_dir() : a.data_dir;
  if (a.simplify) return exec_simplify_benchmark(a, dir);
  if (paths.empty()) {
    for (const char* name : {"bunny_36k.obj", "armadillo_43k.obj", "dragon_50k.ply", "igea_134k.ply.gz"}) {
      std::string p = dir + "/" + name;
      if (std::filesystem::exists(p))
        paths.push_back(p);
      else
        std::fprintf(stderr, "skipped %s: not found (give meshes as arguments or --data-dir)\n", p.c_str());
    }
    if (paths.empty()) throw meshsal::Error("no benchmark meshes found in '" + dir + "'");
  }
  std::vector<Row> rows;
  for (const std::string& p : paths)
    for (const auto& opt : bench_backends(a)) {
      if (!a.json && isatty(fileno(stderr))) std::fprintf(stderr, "  %s ...\r", p.c_str());
      try {
        rows.push_back(bench_one(p, opt, a.repeat));
      } catch (const meshsal::Error& e) {
        if (opt.backend == meshsal::Backend::Cpu) throw;
        std::fprintf(stderr, "skipped %s on Vulkan device %d: %s\n", p.c_str(), opt.device, e.what());
      }
    }
  if (a.json)
    print_json(rows);
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
  sub.add_flag("--json", a->json, "Print JSON instead of the table");
  sub.add_flag("--simplify", a->simplify,
               "Benchmark simplification instead (plain, saliency-weighted, meshoptimizer) at 1% "
               "and 5% of the faces of armadillo_43k, dragon_50k and igea_134k");
  add_threads_option(sub, a->threads, "CPU threads (0 = all cores)");
  sub.add_option("--repeat", a->repeat, "Runs per mesh and device; the fastest is reported")
      ->capture_default_str()->check(whole_in(1, 1000));
  return [a] { return run(*a); };
}

const bool registered = register_command({"bench", "Benchmark saliency stages on real meshes", 40, setup});

}  // namespace
}  // namespace meshsal_cli
