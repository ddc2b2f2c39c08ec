#include "saliency_output.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <CLI/CLI.hpp>

#include "command.h"
#include "json_object.h"
#include "core/mesh_points.h"
#include "io/colormap.h"
#include "meshsal/meshsal.h"

namespace meshsal::cli {

using namespace meshsal;

JsonObject saliency_json(const std::string& input, const std::string& output, const Mesh& mesh,
                         const SaliencyResult& r, double load_seconds) {
  const SaliencyStats st = saliency_stats(r);
  JsonObject stages;
  double total = 0;
  for (const StageTime& s : r.stages) {
    std::string key = s.name;  // "gaussian sweep" -> "gaussian_sweep": keys are snake_case
    for (char& c : key)
      if (c == ' ' || c == '-') c = '_';
    stages.number(key, s.seconds);
    total += s.seconds;
  }
  JsonObject stats;
  stats.number("min", st.min).number("mean", st.mean).number("max", st.max).number("p10", st.p10)
      .number("p50", st.p50).number("p90", st.p90).number("p99", st.p99);
  JsonObject j;
  j.text("mesh", input).text("output", output).count("vertices", mesh.vertex_count()).count("points", st.points)
      .count("faces", mesh.triangle_count()).number("eps", r.eps).text("device", r.backend_name)
      .text("model", meshsal::model_name(r.model)).text("precision", r.mixed_precision ? "mixed" : "double").count("rechecked", r.rechecked)
      .number("read_seconds", load_seconds).number("seconds", total).object("stages", stages)
      .count("pairs", r.pairs).count("tiles", r.tiles).count("ranks", size_t(r.ranks))
      .object("saliency", stats);
  return j;
}

JsonObject out_of_core_json(const std::string& input, const std::string& output,
                            const meshsal::OutOfCoreReport& r, meshsal::Method method, uint64_t memory_limit,
                            double seconds, uint64_t peak_rss) {
  JsonObject stages;
  for (const StageTime& s : r.stages) {
    std::string key = s.name;
    for (char& c : key)
      if (c == ' ' || c == '-') c = '_';
    stages.number(key, s.seconds);
  }
  JsonObject stats;
  stats.number("min", r.saliency_min).number("mean", r.saliency_mean).number("max", r.saliency_max)
      .number("p10", r.saliency_p10).number("p50", r.saliency_p50).number("p90", r.saliency_p90)
      .number("p99", r.saliency_p99);
  JsonObject j;
  j.text("mesh", input).text("output", output).count("vertices", r.vertices).count("points", r.points)
      .count("faces", r.triangles).number("eps", r.eps).text("device", "cpu")
      .text("method", method == Method::Exact ? "exact" : "fast").number("seconds", seconds)
      .object("stages", stages).count("pairs", r.pairs).count("tiles", r.tiles).count("ranks", size_t(r.ranks))
      .count("memory_limit", memory_limit).count("tile_estimate", r.tile_estimate).count("peak_rss", peak_rss)
      .object("saliency", stats);
  return j;
}

void print_saliency_json(const std::string& input, const std::string& output, const Mesh& mesh,
                         const SaliencyResult& r, double load_seconds) {
  saliency_json(input, output, mesh, r, load_seconds).print();
}

void print_saliency_summary(const Mesh& mesh, const SaliencyResult& r, double load_seconds) {
  const SaliencyStats st = saliency_stats(r);
  std::printf("vertices   %zu (%zu on triangles)\n", mesh.vertex_count(), st.points);
  std::printf("faces      %zu triangles\n", mesh.triangle_count());
  std::printf("eps        %.6g\n", r.eps);
  std::printf("backend    %s\n", r.backend_name.c_str());
  if (r.tiles > 0)
    std::printf("tiles      %zu%s\n", r.tiles, r.ranks > 1 ? (" shared by " + std::to_string(r.ranks) + " ranks").c_str() : "");
  if (r.model != meshsal::Model::Lee2005)
    std::printf("model      %s (docs/method.md, \"The perceptual model\")\n", meshsal::model_name(r.model));
  if (r.method == Method::Fast)
    std::printf("method     fast (cell aggregates; error against exact: docs/method.md)\n");
  if (r.mixed_precision)
    std::printf("precision  mixed (%llu points rechecked in double)\n", (unsigned long long)r.rechecked);
  std::printf("read       %8.3f s\n", load_seconds);
  double total = 0;
  for (const StageTime& s : r.stages) {
    std::printf("%-10s %8.3f s\n", s.name.c_str(), s.seconds);  // never cut a stage name
    total += s.seconds;
  }
  std::printf("saliency   %8.3f s total, %.3g neighbour pairs, %.3g pairs/s\n", total,
              double(r.pairs), total > 0 ? double(r.pairs) / total : 0.0);
  std::printf("S          min %g, mean %g, max %g; percentiles 10: %g, 50: %g, 90: %g, 99: %g\n", st.min,
              st.mean, st.max, st.p10, st.p50, st.p90, st.p99);
}

Backend parse_backend(const std::string& name) {
  try {
    return meshsal::parse_backend(name);
  } catch (const meshsal::Error& e) {
    throw UsageError(std::string("--") + e.what());  // "--backend must be auto, cpu or gpu, ..."
  }
}

void add_precision_option(CLI::App& app, std::string* name) {
  app.add_option("--precision", *name,
                 "GPU sweep arithmetic: mixed (float distances and weights, sums and near ties "
                 "in double), double, or auto (mixed on GPUs with slow doubles, timed once per device; "
                 "double on the others, e.g. an H100/H200, and on CPU devices)")
      ->check(CLI::IsMember({"auto", "mixed", "double"}))
      ->capture_default_str();
}

}  // namespace meshsal::cli

namespace meshsal::cli {

void add_method_option(CLI::App& app, std::string* name) {
  app.add_option("--method", *name,
                 "Gaussian averages: exact (every neighbour, cost ~ n x neighbours), fast "
                 "(cell aggregates at sigma/6, linear cost, CPU path; error against exact in "
                 "docs/method.md) or auto (fast when the exact sweep would pass ~2e9 pairs)")
      ->check(CLI::IsMember({"exact", "fast", "auto"}))
      ->capture_default_str();
}

}  // namespace meshsal::cli
