#include "saliency_output.h"

#include <cstdio>

#include <CLI/CLI.hpp>

#include "core/colormap.h"
#include "meshsal/meshsal.h"

namespace meshsal_cli {

using namespace meshsal;

void write_saliency_ply(const std::string& path, const Mesh& mesh, const SaliencyResult& r,
                        bool dump_scales) {
  std::vector<PlyFloatProperty> props{{"quality", &r.saliency}};
  std::vector<std::string> names;
  if (dump_scales) {
    props.push_back({"curvature", &r.curvature});
    for (size_t i = 0; i < r.raw.size(); ++i) names.push_back("saliency_raw_" + std::to_string(i));
    for (size_t i = 0; i < r.raw.size(); ++i) props.push_back({names[i], &r.raw[i]});
  }
  // The pictures' colour scale (ColorRange's default: minimum..maximum, square-root position).
  std::vector<uint8_t> rgb = colormap_values(r.saliency, r.is_point);
  write_ply(path, mesh, props, &rgb);
}

void print_saliency_summary(const Mesh& mesh, const SaliencyResult& r, double load_seconds) {
  size_t points = 0;
  for (uint8_t f : r.is_point) points += f;
  std::printf("vertices   %zu (%zu on triangles)\n", mesh.vertex_count(), points);
  std::printf("faces      %zu triangles\n", mesh.triangle_count());
  std::printf("eps        %.6g\n", r.eps);
  std::printf("backend    %s\n", r.backend_name.c_str());
  if (r.mixed_precision)
    std::printf("precision  mixed (%llu points rechecked in double)\n", (unsigned long long)r.rechecked);
  std::printf("read       %8.3f s\n", load_seconds);
  double total = 0;
  for (const StageTime& s : r.stages) {
    std::printf("%-10.10s %8.3f s\n", s.name.c_str(), s.seconds);
    total += s.seconds;
  }
  std::printf("saliency   %8.3f s total, %.3g neighbour pairs, %.3g pairs/s\n", total,
              double(r.pairs), total > 0 ? double(r.pairs) / total : 0.0);
}

Backend parse_backend(const std::string& name) {
  if (name == "auto") return Backend::Auto;
  if (name == "cpu") return Backend::Cpu;
  if (name == "gpu") return Backend::Gpu;
  throw Error("--backend must be auto, cpu or gpu, got '" + name + "'");
}

void add_precision_option(CLI::App& app, std::string* name) {
  app.add_option("--precision", *name,
                 "GPU sweep arithmetic: mixed (float distances and weights, sums and near ties "
                 "in double), double, or auto (mixed on GPUs, double on CPU devices)")
      ->check(CLI::IsMember({"auto", "mixed", "double"}))
      ->capture_default_str();
}

}  // namespace meshsal_cli
