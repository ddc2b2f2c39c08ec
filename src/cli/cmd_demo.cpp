// meshsal demo -o DIR: the paper's point on a procedural mesh, with no data needed.
#include <cmath>
#include <filesystem>
#include <memory>

#include "command.h"
#include "request_options.h"
#include "json_object.h"
#include "json_string.h"
#include "meshsal/meshsal.h"
#include "cli/render_demo.h"
#include "saliency/saliency.h"
#include "simplify/saliency_weights.h"
#include "simplify/simplify.h"
#include "core/surface_distance.h"
#include "cli/synthetic.h"
#include "number_options.h"
#include "output_check.h"
#include "progress.h"
#include "saliency_output.h"
#include "interrupt.h"

namespace meshsal::cli {
namespace {

struct Args {
  std::string dir = "demo_out";
  int subdivisions = 6;
  RequestText text;  // the options every command shares
};

// Mean distance of the masked vertices of `mesh` to the surface `simplified`.
double mean_distance(const meshsal::Mesh& mesh, const std::vector<uint8_t>& mask,
                     const meshsal::Mesh& simplified) {
  meshsal::TriangleBvh bvh = meshsal::build_triangle_bvh(simplified);
  double sum = 0;
  size_t count = 0;
  for (size_t v = 0; v < mesh.vertex_count(); ++v)
    if (mask[v]) {
      double p[3] = {mesh.positions[3 * v], mesh.positions[3 * v + 1], mesh.positions[3 * v + 2]};
      sum += meshsal::surface_distance(bvh, p), count++;
    }
  return count ? sum / double(count) : 0.0;
}

double mean_over(const std::vector<double>& values, const std::vector<uint8_t>& mask) {
  double sum = 0;
  size_t count = 0;
  for (size_t v = 0; v < values.size(); ++v)
    if (mask[v]) sum += std::fabs(values[v]), count++;
  return count ? sum / double(count) : 0.0;
}

int run(const Args& a) {
  // The human summary: nothing with -q, the JSON object instead with --json.
  const bool human = !a.text.quiet && !a.text.json;
  using namespace meshsal;
  // Before any work: the folder exists (or is made) and is writable.
  prepare_output_folder(a.dir);

  std::vector<uint8_t> feature, bumps;
  Mesh mesh = make_bumpy_sphere(a.subdivisions, &feature, &bumps);
  if (human) std::printf("demo mesh: a sphere with ~900 identical small bumps and one larger unique feature\n");

  // The saliency options as every command reads them (request_from).
  Progress progress(!a.text.quiet && stderr_is_terminal());
  SaliencyOptions opt = request_from(a.text, &progress).saliency;
  opt.smoothed = true;  // Sm = G(S, 3 eps) for the simplification below
  SaliencyResult r = compute_saliency(mesh, opt);
  progress.finish();
  if (human) print_saliency_summary(mesh, r, 0.0);

  const std::string out = a.dir + "/bumpy_sphere_saliency.ply";
  write_saliency(out, mesh, r, true);
  if (human) std::printf("\n                 mean |curvature|   mean saliency\n");
  if (human) std::printf("unique feature   %16.3f   %13.3f\n", mean_over(r.curvature, feature), mean_over(r.saliency, feature));
  if (human) std::printf("repeated bumps   %16.3f   %13.3f\n", mean_over(r.curvature, bumps), mean_over(r.saliency, bumps));
  // The demo's point is the paper's model's; another model's S is only shown.
  if (human && r.model == Model::Lee2005)
    std::printf("Curvature rates the bumps at least as high; saliency singles out the feature.\n");
  if (human && r.model != Model::Lee2005)
    std::printf("S here is --model %s's (docs/method.md, \"The perceptual model\").\n", model_name(r.model));
  if (human) std::printf("wrote %s (open in MeshLab: colour = saliency)\n", printable(out).c_str());

  // Simplification to 4% of the faces, plain quadrics against saliency-weighted ones.
  SimplifyOptions so;
  so.cancel = interrupt_flag();
  so.ratio = 0.04;
  const std::vector<double> weights = saliency_weights(r.smoothed, r.is_point, {}).weights;
  const Mesh plain = simplify_mesh(mesh, so).mesh;
  const Mesh salient = simplify_mesh(mesh, so, weights).mesh;
  write_obj(a.dir + "/simplified_plain.obj", plain);
  write_obj(a.dir + "/simplified_saliency.obj", salient);
  if (human) std::printf("\nsimplified to %zu faces       plain quadrics   saliency-weighted\n",
              salient.triangle_count());
  if (human) std::printf("feature error (mean dist.) %15.5f   %17.5f\n", mean_distance(mesh, feature, plain),
              mean_distance(mesh, feature, salient));
  if (human) std::printf("wrote %s/simplified_plain.obj and simplified_saliency.obj\n", printable(a.dir).c_str());

  // Pictures: best view coloured by saliency, the map of visible saliency over all view
  // directions, and original | plain | saliency-simplified side by side.
  DemoPictureOptions po;
  po.backend = opt.backend;
  progress.update("pictures", 0.0);
  std::vector<std::string> pictures = write_demo_pictures(mesh, r.saliency, a.dir, &plain, &salient, po);
  progress.finish();
  if (human) std::printf("\n");
  for (const std::string& p : pictures)
    if (human) std::printf("wrote %s\n", printable(p).c_str());
  if (a.text.json) {
    std::vector<std::string> outputs{out, a.dir + "/simplified_plain.obj", a.dir + "/simplified_saliency.obj"};
    outputs.insert(outputs.end(), pictures.begin(), pictures.end());
    JsonObject()
        .count("vertices", mesh.vertex_count()).count("faces", mesh.triangle_count())
        .number("feature_curvature", mean_over(r.curvature, feature)).number("feature_saliency", mean_over(r.saliency, feature))
        .number("bumps_curvature", mean_over(r.curvature, bumps)).number("bumps_saliency", mean_over(r.saliency, bumps))
        .number("feature_error_plain", mean_distance(mesh, feature, plain))
        .number("feature_error_saliency", mean_distance(mesh, feature, salient))
        .strings("outputs", outputs).print();
  }
  return 0;
}

RunFn setup(CLI::App& sub) {
  auto a = std::make_shared<Args>();
  sub.footer(
      "Build a procedural mesh that shows the paper's point (a sphere covered with regular small\n"
      "bumps and one unique larger feature), compute its saliency and write the results to DIR.");
  sub.add_option("-o,--output", a->dir, "Output folder (created if missing)")->capture_default_str();
  sub.add_option("--subdivisions", a->subdivisions, "Icosphere subdivisions (5..8; 6 = 41k vertices)")
      ->capture_default_str()->check(whole_in(5, 8));
  add_saliency_options(sub, a->text);
  add_output_flags(sub, a->text, "Print the demo's figures and the files written as one JSON object on stdout");
  return [a] { return run(*a); };
}

const bool registered = register_command({"demo", "Run saliency on the built-in demo mesh", 0, setup});

}  // namespace
}  // namespace meshsal::cli
