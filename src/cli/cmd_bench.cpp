// meshsal bench: time each saliency stage on real meshes, in the style of the paper's Table 1.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <unistd.h>

#include "command.h"
#include "meshsal/error.h"
#include "meshsal/mesh_io.h"
#include "meshsal/saliency.h"

namespace meshsal_cli {
namespace {

struct Args {
  std::vector<std::string> meshes;
  std::string data_dir;
  bool json = false;
  unsigned threads = 0;
  int repeat = 3;
};

struct Row {
  std::string model, device;
  size_t vertices = 0;
  double read = 0;
  meshsal::SaliencyResult best;  // the fastest of the repeats
  double total = 0;
};

// ../shared/data/meshes from the working directory, else relative to the executable.
std::string default_data_dir() {
  const char* env = std::getenv("MESHSAL_DATA");
  if (env && *env) return env;
  namespace fs = std::filesystem;
  if (fs::is_directory("../shared/data/meshes")) return "../shared/data/meshes";
  std::error_code ec;
  fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    fs::path guess = exe.parent_path().parent_path().parent_path() / "shared/data/meshes";
    if (fs::is_directory(guess)) return guess.string();
  }
  return "../shared/data/meshes";
}

// Each backend the table has a row for: the CPU path (and Vulkan devices where built).
std::vector<meshsal::SaliencyOptions> bench_backends(const Args& a) {
  meshsal::SaliencyOptions cpu;
  cpu.backend = meshsal::Backend::Cpu;
  cpu.threads = a.threads;
  return {cpu};
}

Row bench_one(const std::string& path, const meshsal::SaliencyOptions& opt, int repeat) {
  using clock = std::chrono::steady_clock;
  Row row;
  row.model = std::filesystem::path(path).filename().string();
  auto t0 = clock::now();
  meshsal::Mesh mesh = meshsal::load_mesh(path);
  row.read = std::chrono::duration<double>(clock::now() - t0).count();
  row.vertices = mesh.vertex_count();
  for (int i = 0; i < repeat; ++i) {
    meshsal::SaliencyResult r = meshsal::compute_saliency(mesh, opt);
    double total = 0;
    for (const auto& s : r.stages) total += s.seconds;
    if (i == 0 || total < row.total) row.best = std::move(r), row.total = total;
  }
  row.device = row.best.backend_name;
  return row;
}

double stage(const Row& row, const char* name) {
  for (const auto& s : row.best.stages)
    if (s.name == name) return s.seconds;
  return 0.0;
}

void print_table(const std::vector<Row>& rows) {
  std::printf("%-24s %9s  %-22s %9s %9s %9s %9s %9s %10s %10s\n", "model", "vertices", "device",
              "curvature", "sweep", "c-s", "suppress", "total", "pairs", "pairs/s");
  for (const Row& r : rows)
    std::printf("%-24s %9zu  %-22.22s %8.3fs %8.3fs %8.3fs %8.3fs %8.3fs %10.3g %10.3g\n",
                r.model.c_str(), r.vertices, r.device.c_str(), stage(r, "curvature"),
                stage(r, "gaussian sweep"), stage(r, "center-surround"), stage(r, "suppression"),
                r.total, double(r.best.pairs), r.total > 0 ? r.best.pairs / r.total : 0.0);
  std::printf("(saliency only, file reading excluded; best of the repeats)\n");
}

void print_json(const std::vector<Row>& rows) {
  std::printf("[\n");
  for (size_t i = 0; i < rows.size(); ++i) {
    const Row& r = rows[i];
    std::printf("  {\"model\": \"%s\", \"vertices\": %zu, \"device\": \"%s\", \"read_s\": %.6f, \"stages\": {",
                r.model.c_str(), r.vertices, r.device.c_str(), r.read);
    for (size_t s = 0; s < r.best.stages.size(); ++s)
      std::printf("%s\"%s\": %.6f", s ? ", " : "", r.best.stages[s].name.c_str(), r.best.stages[s].seconds);
    std::printf("}, \"total_s\": %.6f, \"pairs\": %llu, \"pairs_per_s\": %.6g}%s\n", r.total,
                (unsigned long long)r.best.pairs, r.total > 0 ? r.best.pairs / r.total : 0.0,
                i + 1 < rows.size() ? "," : "");
  }
  std::printf("]\n");
}

int run(const Args& a) {
  if (a.repeat < 1) throw meshsal::Error("--repeat must be at least 1");
  std::vector<std::string> paths = a.meshes;
  const std::string dir = a.data_dir.empty() ? default_data_dir() : a.data_dir;
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
      rows.push_back(bench_one(p, opt, a.repeat));
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
  sub.add_option("--threads", a->threads, "CPU threads (0 = all cores)")->capture_default_str();
  sub.add_option("--repeat", a->repeat, "Runs per mesh and device; the fastest is reported")
      ->capture_default_str();
  return [a] { return run(*a); };
}

const bool registered = register_command({"bench", "Benchmark saliency stages on real meshes", 40, setup});

}  // namespace
}  // namespace meshsal_cli
