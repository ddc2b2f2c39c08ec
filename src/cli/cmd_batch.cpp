// `meshsal batch`: saliency (and optionally the best-view picture and a simplified mesh) of
// many models in one process: one Vulkan device for the whole run (gpu/gpu_session.h: the
// device is opened and its pipelines compiled once), the next model read while the current
// one computes (batch_loader.h), one output folder, a JSON Lines log (batch_log.h), a
// progress line, resumable, and a failing model logged while the others go on.
#include <sys/stat.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <new>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "api/viewpoint_backend.h"
#include "batch_inputs.h"
#include "batch_loader.h"
#include "batch_log.h"
#include "batch_outputs.h"
#include "batch_progress.h"
#include "command.h"
#include "contact_sheet.h"
#include "core/timer.h"
#include "json_object.h"
#include "json_string.h"
#include "meshsal/meshsal.h"
#include "number_options.h"
#include "output_check.h"
#include "progress.h"
#include "saliency/saliency.h"
#include "saliency_output.h"
#include "view/camera.h"
#include "view/picture.h"
#include "view/render.h"
#include "view/viewpoint.h"
#include "view/visibility.h"
#if MESHSAL_WITH_VULKAN
#include "gpu/gpu_session.h"
#endif

namespace meshsal_cli {
namespace {

using namespace meshsal;

struct Options {
  std::vector<std::string> inputs;
  std::string list_file, out_dir, log, contact_sheet;
  double simplify = 0;  // 0: none; (0, 1]: a ratio of the faces; > 1: a face count
  bool view = false, force = false, quiet = false;
  std::string backend = "auto", precision = "auto", method = "exact", scales = "2,3,4,5,6", up = "y";
  double eps_frac = 0.003;
  unsigned threads = 0;
  int device = -1, size = 512, restarts = 8, resolution = 512;
};

// What one model's run needs besides its mesh.
struct Plan {
  const Options* o;
  SaliencyOptions saliency;
  RenderStyle style;
  Backend backend;
};

// GPU reuse as the log shows it: whether this model opened a device, and how many
// pipelines it compiled (0 for every model after the first on a device).
struct GpuCounts {
  uint64_t opened = 0, kernels = 0;
  static GpuCounts now() {
#if MESHSAL_WITH_VULKAN
    const gpu::SessionCounters c = gpu::session_counters();
    return {c.contexts_opened, c.kernels_built};
#else
    return {};
#endif
  }
};

const double kDeg = 180.0 / 3.14159265358979323846;

std::string file_name(const std::string& path) { return std::filesystem::path(path).filename().string(); }

// The best view (as `meshsal viewpoint`), its picture, and its part of the log line.
JsonObject best_view(const Plan& p, const Mesh& mesh, const SaliencyResult& r, const std::string& input,
                     const std::string& png, BatchProgress& progress) {
  const Timer t;
  VisibilityOptions vopt;
  vopt.resolution = p.o->resolution;
  vopt.threads = p.o->threads;
  OptimiserOptions oopt;
  oopt.restarts = p.o->restarts;
  OptimiserResult best;
  std::string backend_name;
  {
    ViewScorerSetup setup = make_view_scorer(mesh, r.saliency, vopt, p.backend, p.o->device, p.saliency.notice);
    backend_name = setup.backend_name;
    double done = 0;
    const double bound = double(oopt.restarts) * (1 + 5.0 * oopt.max_iterations);
    const ViewScorer scorer = [&](const std::vector<ViewAngles>& views) {
      std::vector<double> u = setup.scorer(views);
      done += double(views.size());
      progress.stage("best view", std::min(1.0, done / bound));
      return u;
    };
    best = optimise_viewpoint(scorer, oopt);
  }  // the device goes back to the session here
  double total = 0;
  for (float w : visibility_weights(mesh, r.saliency)) total += w;
  // Searched in y-up angles; shown in the angles of --up (the same direction).
  const ViewFrame up_frame = frame_mesh(mesh, p.style.up);
  double d[3];
  view_direction(best.best, d);
  const ViewAngles shown = direction_angles(up_frame, d);
  progress.stage("view picture", 0);
  write_png(png, titled_view(mesh, &r.saliency, shown, p.style, file_name(input), "saliency"));
  JsonObject j;
  j.text("output", png).number("theta_deg", shown.theta * kDeg).number("phi_deg", shown.phi * kDeg)
      .raw("direction", "[" + std::to_string(d[0]) + ", " + std::to_string(d[1]) + ", " + std::to_string(d[2]) + "]")
      .number("visible_score", best.U).number("visible_fraction", total > 0 ? best.U / total : 0.0)
      .text("device", backend_name).count("views_evaluated", best.views_evaluated).number("seconds", t.seconds());
  return j;
}

JsonObject simplified(const Plan& p, const Mesh& mesh, const SaliencyResult& r, const std::string& out) {
  SimplifyOptions so;
  so.threads = p.o->threads;
  if (p.o->simplify <= 1)
    so.ratio = p.o->simplify;
  else
    so.target_faces = size_t(p.o->simplify);
  SimplifyReport rep;
  const Timer t;
  const Mesh m = simplify_with_saliency(mesh, so, {}, p.saliency, &r.saliency, &rep);
  write_obj(out, m);
  JsonObject j;
  j.text("output", out).count("faces", rep.output_faces).count("vertices", rep.output_vertices)
      .count("target_faces", rep.target_faces).flag("reached", rep.reached).number("seconds", t.seconds());
  if (!rep.note.empty()) j.text("note", rep.note);
  return j;
}

// One model, loaded: saliency, its PLY, then what was asked. Throws on failure.
JsonObject compute_model(const Plan& p, const LoadedModel& m, const std::string& name,
                         const ModelOutputs& out, BatchProgress& progress) {
  const Timer t;
  const GpuCounts gpu0 = GpuCounts::now();
  const SaliencyResult r = compute_saliency(m.mesh, p.saliency);
  progress.stage("writing", 0);
  const Timer tw;
  write_saliency_ply(out.saliency, m.mesh, r, false);
  const double write_s = tw.seconds();
  JsonObject j = saliency_json(m.path, out.saliency, m.mesh, r, m.seconds);
  j.text("status", "done").text("name", name).number("write_seconds", write_s);
  if (m.welded_corners) j.count("welded_corners", m.welded_corners);
  if (!out.view.empty()) j.object("view", best_view(p, m.mesh, r, m.path, out.view, progress));
  if (!out.simplified.empty()) {
    progress.stage("simplify", 0);
    j.object("simplify", simplified(p, m.mesh, r, out.simplified));
  }
  const GpuCounts gpu1 = GpuCounts::now();
  if (built_with_vulkan())
    j.flag("device_opened", gpu1.opened > gpu0.opened).count("pipelines_built", gpu1.kernels - gpu0.kernels);
  j.number("total_seconds", t.seconds() + m.seconds);
  return j;
}

std::string failed_line(const std::string& input, const std::string& name, const std::string& error) {
  JsonObject j;
  j.text("mesh", input).text("status", "failed").text("name", name).text("error", error);
  return j.str();
}

// "OUT: is the input file 'IN'" when an output of this model is one of the run's inputs.
std::string output_is_an_input(const ModelOutputs& out, const std::set<std::pair<dev_t, ino_t>>& inputs) {
  for (const std::string& path : out.all()) {
    struct stat st;
    if (::stat(path.c_str(), &st) == 0 && inputs.count({st.st_dev, st.st_ino}))
      return path + ": this output is one of the batch's inputs (an output never replaces an input)";
  }
  return "";
}

int run(Options o) {
  if (o.inputs.empty() && o.list_file.empty())
    throw UsageError("give the models: files, folders, globs, @LIST or --list FILE");
  if (o.simplify > 1 && o.simplify != std::floor(o.simplify))
    throw UsageError("--simplify: a value above 1 is a face count and must be a whole number, got " +
                     std::to_string(o.simplify));
  if (!o.contact_sheet.empty()) o.view = true;  // the sheet shows the best-view pictures

  Plan p;
  p.o = &o;
  p.backend = parse_backend(o.backend);
  p.saliency.eps_frac = o.eps_frac;
  p.saliency.scales = parse_scales(o.scales);
  p.saliency.threads = o.threads;
  p.saliency.backend = p.backend;
  p.saliency.precision = parse_precision(o.precision);
  p.saliency.method = parse_method(o.method);
  p.saliency.device = o.device;
  check_saliency_options(p.saliency);
  p.style.size = o.size;
  p.style.up = parse_up_axis(o.up);
  check_render_style(p.style);

  // Before any work: the inputs, the output folder, the log and the sheet.
  const std::vector<std::string> inputs = expand_batch_inputs(o.inputs, o.list_file);
  prepare_output_folder(o.out_dir);
  const std::string log_path = o.log.empty() ? o.out_dir + "/batch.jsonl" : o.log;
  check_outputs({{log_path, "--log", {}}, {o.contact_sheet, "--contact-sheet", {".png"}}}, inputs);
  std::set<std::pair<dev_t, ino_t>> input_ids;
  for (const std::string& in : inputs) {
    struct stat st;
    if (::stat(in.c_str(), &st) == 0) input_ids.insert({st.st_dev, st.st_ino});
  }

  const std::vector<std::string> names = output_names(inputs);
  std::vector<ModelOutputs> outs;
  std::vector<std::string> refused(inputs.size());  // an output that is an input
  std::vector<bool> skip(inputs.size(), false);
  std::vector<std::string> to_load;
  for (size_t i = 0; i < inputs.size(); ++i) {
    outs.push_back(model_outputs(o.out_dir, names[i], o.view, o.simplify > 0));
    refused[i] = output_is_an_input(outs[i], input_ids);
    if (refused[i].empty()) skip[i] = !o.force && outputs_up_to_date(inputs[i], outs[i]);
    if (refused[i].empty() && !skip[i]) to_load.push_back(inputs[i]);
  }

  BatchProgress progress(!o.quiet && stderr_is_terminal(), inputs.size());
  std::set<std::string> told;  // each notice once per run, not once per model
  std::vector<std::string>* model_notes = nullptr;
  p.saliency.progress = [&](const char* stage, double f) { progress.stage(stage, f); };
  p.saliency.notice = [&](const std::string& line) {
    if (model_notes) model_notes->push_back(line);
    if (!o.quiet && told.insert(line).second) {
      progress.clear();
      std::fprintf(stderr, "%s\n", line.c_str());
    }
  };

  BatchLog log(log_path);
  const Timer t_run;
  size_t computed = 0, skipped = 0, failed = 0, left = to_load.size();
  std::unique_ptr<ModelLoader> loader;
  if (!to_load.empty()) loader = std::make_unique<ModelLoader>(to_load);
  for (size_t i = 0; i < inputs.size(); ++i) {
    const std::string& in = inputs[i];
    if (skip[i]) {
      JsonObject j;
      JsonObject files;
      for (const std::string& f : outs[i].all()) files.text(f == outs[i].saliency ? "saliency" : f == outs[i].view ? "view" : "simplified", f);
      j.text("mesh", in).text("status", "skipped").text("name", names[i]).object("outputs", files)
          .text("reason", "every output is newer than the input (--force redoes it)");
      log.add(j.str());
      skipped++;
      continue;
    }
    if (!refused[i].empty()) {
      log.add(failed_line(in, names[i], refused[i]));
      progress.clear();
      std::fprintf(stderr, "error: %s\n", refused[i].c_str());
      failed++;
      continue;
    }
    progress.remaining(--left);
    progress.model(computed + skipped + failed, file_name(in));
    LoadedModel m = loader->next();
    std::vector<std::string> notes;
    model_notes = &notes;
    std::string error = m.error;
    if (error.empty()) {
      try {
        const Timer t;
        JsonObject j = compute_model(p, m, names[i], outs[i], progress);
        if (!notes.empty()) {
          std::string arr = "[";
          for (size_t k = 0; k < notes.size(); ++k) arr += (k ? ", " : "") + json_string(notes[k]);
          j.raw("notes", arr + "]");
        }
        log.add(j.str());
        progress.computed(t.seconds() + m.seconds);
        computed++;
      } catch (const std::bad_alloc&) {
        error = in + ": out of memory";
      } catch (const std::exception& e) {
        error = e.what();
      }
    }
    model_notes = nullptr;
    m.mesh = {};  // free it before the next one is read
    if (!error.empty()) {
      log.add(failed_line(in, names[i], error));
      progress.clear();
      std::fprintf(stderr, "error: %s\n", error.c_str());
      failed++;
    }
  }
  loader.reset();
  progress.clear();
  log.finish();

  if (!o.contact_sheet.empty()) {
    std::vector<SheetItem> items;
    for (size_t i = 0; i < inputs.size(); ++i)
      if (refused[i].empty() && outputs_up_to_date(inputs[i], outs[i]))
        items.push_back({file_name(inputs[i]), outs[i].view});
    if (items.empty()) {
      std::fprintf(stderr, "note: no contact sheet: no model has a best-view picture\n");
    } else {
      write_png(o.contact_sheet, contact_sheet(items));
    }
  }
  if (!o.quiet) {
    std::printf("batch: %zu models: %zu computed, %zu skipped, %zu failed in %.3f s; log %s\n", inputs.size(),
                computed, skipped, failed, t_run.seconds(), log_path.c_str());
    if (!o.contact_sheet.empty()) std::printf("wrote  %s\n", o.contact_sheet.c_str());
    std::fflush(stdout);
  }
  return failed ? 1 : 0;
}

RunFn setup(CLI::App& sub) {
  auto o = std::make_shared<Options>();
  sub.footer(
      "Compute the saliency of many models in one process (one Vulkan device and its compiled\n"
      "pipelines for the whole run; the next model is read while the current one computes).\n"
      "Per model, in DIR: NAME_saliency.ply (as `meshsal saliency`), with --view NAME_view.png\n"
      "(the best view, as `meshsal viewpoint -o`), with --simplify NAME_simplified.obj. NAME is\n"
      "the file name without its extension (the whole name, or a _2.. suffix, where two inputs\n"
      "share it). DIR/batch.jsonl (or --log) gets one JSON object per model: its input, status\n"
      "(done, skipped, failed), outputs, counts, seconds per stage, saliency statistics as\n"
      "`saliency --json` prints them, the best view, the device; or `error` with the message.\n"
      "A model whose outputs all exist and are newer than its input is skipped (--force redoes\n"
      "it). A failing model is logged and the others go on; the exit status is 1 when any\n"
      "failed. Inputs: files, folders (the mesh files inside, sorted by name), quoted globs\n"
      "('scans/*.ply'), @LIST or --list LIST (one item per line, # comments; relative items are\n"
      "taken from the list's folder).");
  sub.add_option("inputs", o->inputs, "Mesh files, folders, globs or @LIST files");
  sub.add_option("--list", o->list_file, "A file listing the inputs, one per line");
  sub.add_option("-o,--output", o->out_dir, "Output folder (made if missing)")->required();
  sub.add_option("--log", o->log, "The JSON Lines log (default DIR/batch.jsonl)");
  sub.add_flag("--view", o->view, "Also write the best-view picture NAME_view.png");
  sub.add_option("--simplify", o->simplify,
                 "Also write NAME_simplified.obj with saliency weights: a ratio of the faces in (0, 1], "
                 "or a face count above 1")->check(finite_in(0, 1e12, true));
  sub.add_option("--contact-sheet", o->contact_sheet,
                 "One PNG of every model's best-view picture as a thumbnail with its name (implies --view)");
  sub.add_flag("--force", o->force, "Recompute models whose outputs are up to date");
  sub.add_option("--backend", o->backend, "auto (a GPU when present, else the CPU), gpu or cpu")
      ->capture_default_str()->check(CLI::IsMember({"auto", "cpu", "gpu"}));
  add_precision_option(sub, &o->precision);
  add_method_option(sub, &o->method);
  sub.add_option("--device", o->device, "Vulkan device index for the gpu backend (see `meshsal devices`)")
      ->check(whole_in(-1, 255));
  sub.add_option("--scales", o->scales, "Center-surround scales in units of eps")
      ->capture_default_str()->check(scales_list());
  sub.add_option("--eps-frac", o->eps_frac, "eps as a fraction of the bounding-box diagonal")
      ->capture_default_str()->check(finite_in(0, meshsal::kMaxEpsFrac, true));
  add_threads_option(sub, o->threads, "CPU threads (0 = all cores)");
  sub.add_option("--size", o->size, "side of the best-view picture in pixels")
      ->capture_default_str()->check(whole_in(16, 8192));
  sub.add_option("--restarts", o->restarts, "best view: gradient-ascent restarts")
      ->capture_default_str()->check(whole_in(1, 1000));
  sub.add_option("--resolution", o->resolution, "best view: z-buffer side in pixels")
      ->capture_default_str()->check(whole_in(16, 8192));
  sub.add_option("--up", o->up, "mesh axis that points up in the pictures: x, y, z, -x, -y or -z")
      ->capture_default_str()->check(CLI::IsMember({"x", "y", "z", "-x", "-y", "-z"}));
  sub.add_flag("-q,--quiet", o->quiet, "Print nothing but errors (no progress, notes or summary)");
  return [o] { return run(*o); };
}

const bool registered = register_command({"batch", "Saliency (and best views, simplified meshes) of many models", 15, setup});

}  // namespace
}  // namespace meshsal_cli
