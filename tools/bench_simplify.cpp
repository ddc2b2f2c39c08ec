// bench_simplify: quality and speed of simplification on real meshes, side by side:
// plain quadric error (--weights none), saliency-weighted (SPEC 2) and meshoptimizer's
// meshopt_simplify (when built with it). `meshsal bench --simplify` (cmd_bench_simplify.cpp)
// does the same and more: the balanced preset, a sweep of the weighting, the plot.
//
//   bench_simplify [MESHES...] [--data-dir DIR] [--ratios 0.01,0.05] [--repeat 3]
//                  [--threads N] [--samples N] [--json]
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "cli/data_dir.h"
#include "meshsal/meshsal.h"
#include "saliency/saliency.h"
#include "simplify/saliency_weights.h"
#include "simplify/simplify.h"
#include "simplify/surface_distance.h"
#include "core/timer.h"
#include "json_string.h"

#ifdef MESHSAL_HAVE_MESHOPTIMIZER
#include <meshoptimizer.h>
#endif

using namespace meshsal;
using meshsal_cli::json_string;

namespace {

struct Args {
  std::vector<std::string> meshes;
  std::string data_dir;
  std::vector<double> ratios{0.01, 0.05};
  int repeat = 3;
  unsigned threads = 0;
  size_t samples = 200000;
  bool json = false;
};

struct Row {
  std::string model, method;
  double ratio = 0;
  size_t faces_in = 0, target = 0, faces_out = 0;
  double seconds = 0;  // best of the repeats
  SurfaceComparison cmp;
};

std::vector<double> parse_list(const std::string& text) {
  std::vector<double> out;
  size_t i = 0;
  while (i <= text.size()) {
    size_t j = text.find(',', i);
    if (j == std::string::npos) j = text.size();
    const std::string item = text.substr(i, j - i);
    char* end = nullptr;
    const double v = std::strtod(item.c_str(), &end);
    if (item.empty() || *end || !(v > 0 && v <= 1)) throw Error("bad ratio '" + item + "' in --ratios");
    out.push_back(v);
    i = j + 1;
  }
  return out;
}

Args parse(int argc, char** argv) {
  Args a;
  for (int i = 1; i < argc; ++i) {
    const std::string s = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) throw Error(s + " needs a value");
      return argv[++i];
    };
    if (s == "--data-dir") a.data_dir = value();
    else if (s == "--ratios") a.ratios = parse_list(value());
    else if (s == "--repeat") a.repeat = std::atoi(value().c_str());
    else if (s == "--threads") a.threads = unsigned(std::atoi(value().c_str()));
    else if (s == "--samples") a.samples = size_t(std::atoll(value().c_str()));
    else if (s == "--json") a.json = true;
    else if (s == "--simplify") {}  // passed through from `meshsal bench --simplify`
    else if (s == "-h" || s == "--help") {
      std::printf(
          "bench_simplify [MESHES...] [--data-dir DIR] [--ratios 0.01,0.05] [--repeat 3]\n"
          "               [--threads N] [--samples N] [--json]\n"
          "Simplifies each mesh to each ratio of its faces with --weights none, --weights\n"
          "saliency and meshopt_simplify; reports time (best of --repeat), Hausdorff, RMS and\n"
          "the salient-region error (mean distance of the original's top 30%% salient vertices).\n"
          "Default meshes: armadillo_43k.obj dragon_50k.ply igea_134k.ply.gz.\n");
      std::exit(0);
    } else if (!s.empty() && s[0] == '-') throw Error("unknown option " + s);
    else a.meshes.push_back(s);
  }
  if (a.repeat < 1) throw Error("--repeat must be at least 1");
  return a;
}

// One method to time: its best time over the rounds and its last output.
struct Timed {
  const char* method;
  std::function<Mesh()> run;
  double seconds = 1e30;
  Mesh out;
};

// Runs every method once per round, `repeat` rounds, and keeps each one's best time. The
// methods take turns so that a slow spell of a shared machine falls on all of them alike,
// not on the three runs of one.
void best_of_interleaved(int repeat, std::vector<Timed>& methods) {
  for (int i = 0; i < repeat; ++i)
    for (Timed& m : methods) {
      const meshsal::Timer t0;
      m.out = m.run();
      m.seconds = std::min(m.seconds, t0.seconds());
    }
}

#ifdef MESHSAL_HAVE_MESHOPTIMIZER
Mesh meshopt(const Mesh& in, size_t target_faces) {
  std::vector<unsigned int> dst(in.triangles.size());
  float err = 0;
  // target_error 1 (= the whole extent): bounded only by the face count, like ours.
  const size_t n = meshopt_simplify(dst.data(), in.triangles.data(), in.triangles.size(),
                                    in.positions.data(), in.vertex_count(), 3 * sizeof(float),
                                    3 * target_faces, 1.0f, 0, &err);
  dst.resize(n);
  Mesh out;
  std::vector<uint32_t> remap(in.vertex_count(), UINT32_MAX);
  for (unsigned int& v : dst) {
    if (remap[v] == UINT32_MAX) {
      remap[v] = uint32_t(out.positions.size() / 3);
      out.positions.insert(out.positions.end(), &in.positions[3 * size_t(v)], &in.positions[3 * size_t(v)] + 3);
    }
    out.triangles.push_back(remap[v]);
  }
  return out;
}
#endif

void print_table(const std::vector<Row>& rows) {
  std::printf("%-18s %6s %-9s %8s %8s %9s %10s %10s %10s  %s\n", "model", "ratio", "method",
              "target", "faces", "time", "hausdorff", "rms", "salient", "(distances in % of the bbox diagonal)");
  for (const Row& r : rows) {
    const double d = r.cmp.diagonal > 0 ? 100 / r.cmp.diagonal : 1;
    std::printf("%-18s %5.0f%% %-9s %8zu %8zu %8.3fs %9.4f%% %9.4f%% %9.4f%%\n", r.model.c_str(),
                100 * r.ratio, r.method.c_str(), r.target, r.faces_out, r.seconds,
                r.cmp.hausdorff * d, r.cmp.rms * d, r.cmp.salient_error * d);
  }
  // The targets: salient error with saliency <= 0.8x plain; time within 3x of meshoptimizer.
  std::printf("\n%-18s %6s %22s %22s %22s\n", "model", "ratio", "salient: sal / none",
              "time: none / meshopt", "time: sal / meshopt");
  for (size_t i = 0; i < rows.size(); ++i) {
    if (rows[i].method != "none") continue;
    const Row* sal = nullptr;
    const Row* mo = nullptr;
    for (const Row& r : rows)
      if (r.model == rows[i].model && r.ratio == rows[i].ratio) {
        if (r.method == "saliency") sal = &r;
        if (r.method == "meshopt") mo = &r;
      }
    std::printf("%-18s %5.0f%% %22.3f", rows[i].model.c_str(), 100 * rows[i].ratio,
                sal ? sal->cmp.salient_error / rows[i].cmp.salient_error : 0.0);
    if (mo)
      std::printf(" %22.2f %22.2f\n", rows[i].seconds / mo->seconds, sal ? sal->seconds / mo->seconds : 0.0);
    else
      std::printf(" %22s %22s\n", "-", "-");
  }
}

void print_json(const std::vector<Row>& rows, const std::vector<std::pair<std::string, double>>& sal_times) {
  std::printf("{\"saliency_seconds\": {");
  for (size_t i = 0; i < sal_times.size(); ++i)
    std::printf("%s%s: %.6f", i ? ", " : "", json_string(sal_times[i].first).c_str(), sal_times[i].second);
  std::printf("},\n \"runs\": [\n");
  for (size_t i = 0; i < rows.size(); ++i) {
    const Row& r = rows[i];
    std::printf(
        "  {\"model\": %s, \"ratio\": %g, \"method\": \"%s\", \"faces_in\": %zu, \"target\": %zu, "
        "\"faces\": %zu, \"seconds\": %.6f, \"diagonal\": %.9g, \"hausdorff\": %.9g, \"rms\": %.9g, "
        "\"salient_error\": %.9g}%s\n",
        json_string(r.model).c_str(), r.ratio, r.method.c_str(), r.faces_in, r.target, r.faces_out, r.seconds,
        r.cmp.diagonal, r.cmp.hausdorff, r.cmp.rms, r.cmp.salient_error, i + 1 < rows.size() ? "," : "");
  }
  std::printf("]}\n");
}

int run(const Args& a) {
  std::vector<std::string> paths = a.meshes;
  const std::string dir = a.data_dir.empty() ? meshsal::benchmark_data_dir() : a.data_dir;
  if (paths.empty()) {
    for (const char* name : {"armadillo_43k.obj", "dragon_50k.ply", "igea_134k.ply.gz"}) {
      const std::string p = dir + "/" + name;
      if (std::filesystem::exists(p)) paths.push_back(p);
      else std::fprintf(stderr, "skipped %s: not found (give meshes as arguments or --data-dir)\n", p.c_str());
    }
    if (paths.empty()) throw Error("no benchmark meshes found in '" + dir + "'");
  }
#ifndef MESHSAL_HAVE_MESHOPTIMIZER
  std::fprintf(stderr, "note: built without meshoptimizer; its column is left out\n");
#endif
  std::vector<Row> rows;
  std::vector<std::pair<std::string, double>> sal_times;
  for (const std::string& path : paths) {
    const std::string model = std::filesystem::path(path).filename().string();
    const Mesh mesh = load_mesh(path);
    SaliencyOptions so;
    so.backend = Backend::Cpu;
    so.threads = a.threads;
    const meshsal::Timer ts;
    const SaliencyResult s = compute_saliency(mesh, so);
    const std::vector<double> w = simplification_weights(mesh, {}, so, &s.saliency);
    sal_times.push_back({model, ts.seconds()});
    CompareOptions co;
    co.threads = a.threads;
    co.face_samples = a.samples;
    for (double ratio : a.ratios) {
      SimplifyOptions opt;
      opt.ratio = ratio;
      const size_t target = resolve_target_faces(opt, mesh.triangle_count());
      auto add = [&](const char* method, const Mesh& out, double seconds) {
        Row r;
        r.model = model;
        r.method = method;
        r.ratio = ratio;
        r.faces_in = mesh.triangle_count();
        r.target = target;
        r.faces_out = out.triangle_count();
        r.seconds = seconds;
        r.cmp = compare_surfaces(mesh, out, &s.saliency, co);
        rows.push_back(r);
        if (!a.json) std::fprintf(stderr, "  %s %g %s: %.3f s\n", model.c_str(), ratio, method, seconds);
      };
      std::vector<Timed> methods;
      methods.push_back({"none", [&] { return simplify_mesh(mesh, opt); }});
      methods.push_back({"saliency", [&] { return simplify_mesh(mesh, opt, &w); }});
#ifdef MESHSAL_HAVE_MESHOPTIMIZER
      methods.push_back({"meshopt", [&] { return meshopt(mesh, target); }});
#endif
      best_of_interleaved(a.repeat, methods);
      for (const Timed& m : methods) add(m.method, m.out, m.seconds);
    }
  }
  if (a.json) {
    print_json(rows, sal_times);
  } else {
    print_table(rows);
    std::printf("\nsaliency (CPU, computed once per model, not in the times above):");
    for (auto& [m, t] : sal_times) std::printf(" %s %.2fs", m.c_str(), t);
    std::printf("\ntimes: simplification alone, file reading excluded, best of %d rounds (the three\n"
                "methods take turns in each round)\n", a.repeat);
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return run(parse(argc, argv));
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  }
}
