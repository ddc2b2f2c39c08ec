// `meshsal batch`: saliency (and optionally the best-view picture and a simplified mesh) of
// many models in one process: one Vulkan device for the whole run (gpu/gpu_session.h: the
// device is opened and its pipelines compiled once), the next model read while the current
// one computes (batch_loader.h), one output folder, a JSON Lines log (batch_log.h), a
// progress line, resumable, and a failing model logged while the others go on.
#include <sys/stat.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <memory>
#include <new>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "core/parallel.h"
#include "api/viewpoint_backend.h"
#include "core/mesh_points.h"
#include "batch_inputs.h"
#include "batch_loader.h"
#include "core/peak_memory.h"
#include "batch_log.h"
#include "batch_output_clash.h"
#include "batch_outputs.h"
#include "batch_progress.h"
#include "batch_ranks.h"
#include "batch_state.h"
#include "command.h"
#include "contact_sheet.h"
#include "gallery_page.h"
#include "core/timer.h"
#include "io/atomic_write.h"
#include "json_object.h"
#include "json_string.h"
#include "meshsal/meshsal.h"
#include "number_options.h"
#include "output_check.h"
#include "progress.h"
#include "saliency/saliency.h"
#include "request_options.h"
#include "saliency_output.h"
#include "view/camera.h"
#include "view/picture.h"
#include "view/render.h"
#include "view/viewpoint.h"
#include "view/visibility.h"
#include "interrupt.h"
#include "mpi_world.h"
#if MESHSAL_WITH_VULKAN
#include "gpu/gpu_session.h"
#endif

namespace meshsal::cli {
namespace {

using namespace meshsal;

struct Options {
  std::vector<std::string> inputs;
  std::string list_file, out_dir, log, contact_sheet;
  double simplify = 0;  // 0: none; (0, 1]: a ratio of the faces; > 1: a face count
  double target_error = 0;  // --target-error, % of the bounding-box diagonal (0: none)
  bool lock_border = false;
  bool view = false, force = false;
  bool html = false;  // --html: NAME_view.html per model and the gallery DIR/index.html
  std::string lod;    // --lod LIST: NAME_lod.glb per model, as `simplify --lod LIST -o NAME_lod.glb`
  bool weight_floor_given = false;  // --weight-floor (the state records -1 for the weighting's own)
  RequestText text;  // the options every command shares
};

// What one model's run needs besides its mesh: the request every model makes (its input
// and outputs filled per model).
struct Plan {
  const Options* o;
  bool simplifying = false;  // --simplify or --target-error
  meshsal::Request request;
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
// --html: the viewer (three.js and web/viewer.js) once beside the gallery, which every
// model page loads, rather than inline in each.
const char* const kViewerFile = "meshsal-viewer.js";

// The seconds of a step of the request ("views", "simplify", ...), 0 when it did not run.
double step_seconds(const RequestResult& r, const std::string& name) {
  for (const StageTime& s : r.steps)
    if (s.name == name) return s.seconds;
  return 0;
}

// The best view's part of the log line (as `meshsal viewpoint`).
JsonObject view_json(const RequestResult& res, const std::string& png) {
  const Viewpoint& best = res.viewpoint;
  const double* d = best.camera.direction;
  JsonObject j;
  j.text("output", png).number("theta_deg", best.view.theta * kDeg).number("phi_deg", best.view.phi * kDeg)
      .raw("direction", "[" + std::to_string(d[0]) + ", " + std::to_string(d[1]) + ", " + std::to_string(d[2]) + "]")
      .number("visible_score", best.U).number("visible_fraction", best.visible_fraction)
      .text("device", best.backend_name).count("views_evaluated", best.optimised.views_evaluated)
      .number("seconds", step_seconds(res, "views"));
  if (!best.note.empty()) j.text("note", best.note);
  return j;
}

// The simplified mesh's part: as `meshsal simplify IN -o OUT` makes it with the same options.
JsonObject simplified_json(const Plan& p, const RequestResult& res, const std::string& out) {
  const SimplifyReport& rep = res.simplify;
  JsonObject j;
  const std::string lost = mesh_output_note(out, res.simplified, false);
  if (!lost.empty()) j.text("output_note", lost);
  j.text("output", out).count("faces", rep.output_faces).count("vertices", rep.output_vertices)
      .count("target_faces", rep.target_faces).flag("reached", rep.reached).flag("unchanged", rep.unchanged)
      .number("error_percent", 100 * rep.error);
  if (p.request.out_of_core.memory_limit)
    j.count("tiles", res.simplify_out_of_core.tiles).count("peak_rss", meshsal::peak_resident_bytes());
  if (p.o->target_error > 0) j.number("target_error_percent", p.o->target_error);
  if (p.o->lock_border) j.flag("lock_border", true);
  if (!res.simplified.attributes.empty()) j.count("attributes", res.simplified.attributes.size());
  j.number("seconds", step_seconds(res, "simplify"));
  if (!rep.note.empty()) j.text("note", rep.note);
  return j;
}

// One model: its request (the saliency PLY, then what was asked) and its log line. Throws
// on failure.
JsonObject compute_model(const Plan& p, const LoadedModel& m, const std::string& name,
                         const ModelOutputs& out, BatchProgress& progress) {
  Request r = p.request;
  r.input = m.path;
  if (!p.request.out_of_core.memory_limit) {
    // Read ahead by the loader (ModelLoader): plainly, and with its attributes for the
    // meshes that carry them.
    r.mesh = &m.mesh;
    if (m.has_attributed) r.attributed = &m.attributed;
    else if (!m.attributed_error.empty() && (!out.simplified.empty() || !out.lod.empty())) throw Error(m.attributed_error);
  }
  r.saliency_output = out.saliency;
  r.picture_output = out.view;
  r.page_output = out.page;
  r.find_view = !out.view.empty() || !out.page.empty();
  r.simplified_output = out.simplified;
  r.lod_output = out.lod;
  r.saliency.progress = [&progress](const char* stage, double f) { progress.stage(stage, f); };
  r.viewpoint.optimiser.progress = r.saliency.progress;
  const GpuCounts gpu0 = GpuCounts::now();
  const RequestResult res = run_request(r);
  JsonObject j;
  if (p.request.out_of_core.memory_limit) {
    j = out_of_core_json(m.path, out.saliency, res.out_of_core, r.saliency.method, r.out_of_core.memory_limit,
                         step_seconds(res, "saliency output"), meshsal::peak_resident_bytes());
  } else {
    double computing = 0;
    for (const StageTime& st : res.saliency.stages) computing += st.seconds;
    j = saliency_json(m.path, out.saliency, m.mesh, res.saliency, m.seconds);
    j.number("write_seconds", std::max(0.0, step_seconds(res, "saliency output") - computing));
  }
  j.text("status", "done").text("name", name);
  if (m.welded_corners) j.count("welded_corners", m.welded_corners);
  if (!out.view.empty()) j.object("view", view_json(res, out.view));
  if (!out.page.empty()) j.text("page", out.page);
  if (!out.simplified.empty()) j.object("simplify", simplified_json(p, res, out.simplified));
  if (!out.lod.empty()) {
    std::string faces = "[";
    for (size_t i = 0; i < res.lod.size(); ++i) faces += (i ? ", " : "") + std::to_string(res.lod[i].report.output_faces);
    j.object("lod", JsonObject().text("output", out.lod).raw("faces", faces + "]").number("seconds",
                                                                                         step_seconds(res, "levels of detail")));
  }
  const GpuCounts gpu1 = GpuCounts::now();
  if (built_with_vulkan() && !p.request.out_of_core.memory_limit)
    j.flag("device_opened", gpu1.opened > gpu0.opened).count("pipelines_built", gpu1.kernels - gpu0.kernels);
  j.strings("outputs", res.outputs).number("total_seconds", res.seconds + m.seconds);
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

// Why an input is not read: "" for a regular file (and for a missing one: loading it fails
// with its own message). A named pipe would block the loader until something writes to
// it, a device never ends.
std::string not_read_reason(const std::string& input) {
  struct stat st;
  if (::stat(input.c_str(), &st) != 0 || S_ISREG(st.st_mode)) return "";
  const char* kind = S_ISFIFO(st.st_mode)  ? "a named pipe (FIFO)"
                     : S_ISCHR(st.st_mode) ? "a character device"
                     : S_ISBLK(st.st_mode) ? "a block device"
                     : S_ISSOCK(st.st_mode) ? "a socket"
                     : S_ISDIR(st.st_mode) ? "a folder"
                                           : "not a regular file";
  return std::string("it is ") + kind + ": batch reads regular files only";
}

// Everything that shapes a model's outputs, as one line (batch_state.h): a change in any of
// them makes the model out of date.
std::string options_line(const Options& o) {
  const RequestText& t = o.text;
  char buf[512];
  std::snprintf(buf, sizeof buf,
                "version=%d method=%s scales=%s eps_frac=%.17g precision=%s backend=%s device=%d view=%d "
                "size=%d restarts=%d resolution=%d up=%s simplify=%.17g weights=%s weight_floor=%.17g",
                MESHSAL_VERSION, t.method.c_str(), t.scales.c_str(), t.eps_frac, t.precision.c_str(),
                t.backend.c_str(), t.device, int(o.view || o.html), t.size, t.restarts, t.resolution, t.up.c_str(),
                o.simplify, t.weights.c_str(), o.weight_floor_given ? t.weight_floor : -1.0);
  std::string line = buf;
  // Only where a simplified mesh is made, so that the records of runs without one still
  // hold (a simplified mesh carries the input's attributes since these options came).
  if (o.simplify > 0 || o.target_error > 0) {
    std::snprintf(buf, sizeof buf, " target_error=%.17g lock_border=%d attributes=1 materials=1", o.target_error,
                  int(o.lock_border));
    line += buf;
  }
  // Only when not the defaults, so that the records of earlier runs stay up to date.
  if (o.html) line += " html=1";
  if (t.model != "lee2005") line += " model=" + std::string(meshsal::model_name(meshsal::parse_model(t.model)));
  if (!o.lod.empty()) line += " lod=" + o.lod + " lock_border=" + std::to_string(int(o.lock_border));
  if (!t.elevation.empty()) line += " elevation=" + t.elevation;
  if (!t.color_range.empty()) line += " color_range=" + t.color_range;
  if (t.score != "saliency") line += " score=" + t.score;
  if (t.lambda_given) line += " lambda=" + std::to_string(t.lambda);
  if (t.alpha_given) line += " alpha_percentile=" + std::to_string(t.alpha_percentile);
  if (t.seed != 1) line += " seed=" + std::to_string(t.seed);
  if (t.depth_tol != 2.0) {
    char tol[40];
    std::snprintf(tol, sizeof tol, " depth_tol=%.17g", t.depth_tol);
    line += tol;
  }
  return line;
}

// The sizes of the outputs just written, in ModelOutputs::all() order.
std::vector<uint64_t> output_sizes(const ModelOutputs& out) {
  std::vector<uint64_t> sizes;
  for (const std::string& path : out.all()) {
    struct stat st;
    sizes.push_back(::stat(path.c_str(), &st) == 0 ? uint64_t(st.st_size) : 0);
  }
  return sizes;
}

// The log line of a model skipped as up to date: the record of the run that made its
// outputs (its numbers stay), with the status "skipped" and the reason.
std::string skipped_line(const std::string& record) {
  std::string line = record;
  const std::string done = "\"status\": \"done\"";
  const size_t at = line.find(done);
  if (at != std::string::npos) line.replace(at, done.size(), "\"status\": \"skipped\"");
  if (!line.empty() && line.back() == '}')
    line.insert(line.size() - 1, ", \"reason\": " + json_string("up to date: the same input (size, time and content) "
                                                                 "and options made its outputs (--force redoes it)"));
  return line;
}

// Under MPI: every rank must share out the same models (the same inputs, options and files
// up to date), or some model would be computed twice or never. Each rank sees every
// rank's hash, so all of them stop alike (main: mpi_abort) instead of waiting.
void check_same_models(const std::vector<std::string>& inputs, const std::string& options,
                       const std::vector<size_t>& to_compute) {
  if (meshsal::cli::mpi_world().size < 2) return;
  uint64_t h = 1469598103934665603ull;  // FNV-1a
  const auto mix = [&h](const std::string& s) {
    for (unsigned char c : s) h = (h ^ c) * 1099511628211ull;
    h = (h ^ 0xff) * 1099511628211ull;  // a separator no text holds
  };
  for (const std::string& in : inputs) mix(in);
  mix(options);
  for (size_t i : to_compute) mix(std::to_string(i));
  std::vector<uint8_t> mine(8);
  for (int b = 0; b < 8; ++b) mine[size_t(b)] = uint8_t(h >> (8 * b));
  const std::vector<std::vector<uint8_t>> all = meshsal::cli::mpi_all_gather(mine);
  for (size_t r = 1; r < all.size(); ++r)
    if (all[r] != all[0])
      throw Error("batch: rank " + std::to_string(r) + " has other models to compute than rank 0 (other inputs, "
                  "options, or files it sees): give every rank the same command, on folders every machine sees "
                  "at the same path");
}

// Every rank ends with rank 0's exit status, after rank 0 has written everything (no rank
// leaves before it, which would let mpirun end the job early).
int agreed_status(int status) {
  if (!meshsal::cli::mpi_world().active) return status;
  std::vector<uint8_t> mine(1, uint8_t(status));
  return meshsal::cli::mpi_all_gather(mine)[0][0];
}

// The checks of the options alone, before anything is read; --contact-sheet implies --view.
void check_options(Options& o) {
  {
    // A build without MPI started as N copies would run the whole batch N times at once.
    const int launched = meshsal::cli::mpi_launcher_size();
    if (!meshsal::cli::mpi_world().active && launched > 1)
      throw Error("batch: this meshsal was built without MPI (MESHSAL_WITH_MPI), yet started as " +
                  std::to_string(launched) + " processes: each would run the whole batch; run one, or "
                  "build with MPI");
  }
  if (o.inputs.empty() && o.list_file.empty())
    throw UsageError("give the models: files, folders, globs, @LIST or --list FILE");
  if (o.simplify > 1 && o.simplify != std::floor(o.simplify))
    throw UsageError("--simplify: a value above 1 is a face count and must be a whole number, got " +
                     std::to_string(o.simplify));
  if (o.lock_border && o.simplify == 0 && o.target_error == 0 && o.lod.empty())
    throw UsageError("--lock-border needs --simplify, --target-error or --lod");
  if (!o.lod.empty() && !o.text.memory_limit.empty())
    throw UsageError("--lod simplifies each model in memory: not with --memory-limit");
  // Out of core the mesh is never whole in memory: the saliency PLY, and with --simplify
  // NAME_simplified.ply as `simplify --memory-limit` writes it, are all a model gets.
  if (!o.text.memory_limit.empty() && (o.view || o.html || !o.contact_sheet.empty() || o.target_error > 0))
    throw UsageError("--memory-limit computes each model out of core: it takes no --view, --html, --contact-sheet "
                     "(they need the mesh in memory) or --target-error (give --simplify RATIO|FACES)");
  if (!o.contact_sheet.empty()) o.view = true;  // the sheet shows the best-view pictures
}

// The request every model makes, from the options (its input and outputs filled per model).
Plan make_plan(const Options& o) {
  Plan p;
  p.o = &o;
  p.simplifying = o.simplify > 0 || o.target_error > 0;
  Request& req = p.request;
  req = request_from(o.text, nullptr);
  req.saliency.raw_maps = false;  // no command of batch writes them
  if (o.simplify > 1) req.simplify.target_faces = size_t(o.simplify);
  else if (o.simplify > 0) req.simplify.ratio = o.simplify;
  req.simplify.target_error = o.target_error / 100;
  req.simplify.lock_border = o.lock_border;
  if (!o.lod.empty()) req.lod = parse_lod_levels(o.lod);
  // The model pages share one viewer file beside the gallery (kViewerFile).
  if (o.html) req.page.viewer_script = kViewerFile;
  check_render_style(req.style);
  return p;
}

// The run's models and the files each writes, every output checked before any work.
struct Models {
  std::vector<std::string> inputs, names;  // names: NAME of each model's outputs
  std::vector<ModelOutputs> outs;
  std::string log_path, gallery;  // gallery: "" without --html
  std::string viewer;             // DIR/meshsal-viewer.js, the pages' script: "" without --html
  // Whether an input lives in the output folder: then a model's state file is made before
  // its outputs, so that they are known for outputs even when the run stops part way.
  bool inputs_in_output_folder = false;
  std::set<std::pair<dev_t, ino_t>> input_ids;  // the inputs' files
};

// Whether one of `inputs` lies in the folder `dir` itself (through a link too).
bool any_input_in_folder(const std::vector<std::string>& inputs, const std::string& dir) {
  bool found = false;
  struct stat ds;
  if (::stat(dir.c_str(), &ds) == 0)
    for (const std::string& in : inputs) {
      const std::string folder = std::filesystem::path(in).parent_path().string();
      struct stat fs;
      if (::stat(folder.empty() ? "." : folder.c_str(), &fs) == 0 && fs.st_dev == ds.st_dev && fs.st_ino == ds.st_ino)
        found = true;
    }
  return found;
}

// Before any work: the inputs, the output folder, the log, the sheet and the gallery.
Models find_models(const Options& o, const Plan& p) {
  Models ms;
  std::vector<std::string>& inputs = ms.inputs;
  inputs = expand_batch_inputs(o.inputs, o.list_file);
  prepare_output_folder(o.out_dir);
  // An input folder that is also the output folder: what earlier runs wrote there is no input.
  inputs = without_batch_outputs(inputs, o.out_dir);
  if (inputs.empty())
    throw Error("batch: no mesh file found in the inputs given besides the outputs of earlier runs in " + o.out_dir);
  ms.inputs_in_output_folder = any_input_in_folder(inputs, o.out_dir);
  ms.log_path = o.log.empty() ? o.out_dir + "/batch.jsonl" : o.log;
  ms.gallery = o.html ? o.out_dir + "/index.html" : "";
  ms.viewer = o.html ? o.out_dir + "/" + kViewerFile : "";
  ms.names = output_names(inputs);
  for (size_t i = 0; i < inputs.size(); ++i)
    ms.outs.push_back(model_outputs(o.out_dir, ms.names[i], o.view || o.html, p.simplifying,
                                    p.request.out_of_core.memory_limit != 0, o.html, !p.request.lod.empty()));
  check_batch_outputs_apart(o.out_dir,
                            {{ms.log_path, "--log"}, {o.contact_sheet, "--contact-sheet"}, {ms.gallery, "--html's gallery"},
                             {ms.viewer, "--html's viewer script"}},
                            inputs, ms.names, ms.outs);
  // The list files are inputs too: the log appended to one would be read as models next time.
  std::vector<std::string> read = inputs;
  if (!o.list_file.empty() && o.list_file != "-") read.push_back(o.list_file);
  for (const std::string& item : o.inputs)
    if (item.size() > 1 && item[0] == '@') read.push_back(item.substr(1));
  check_outputs({{ms.log_path, "--log", {}}, {o.contact_sheet, "--contact-sheet", {".png"}}, {ms.gallery, "--html", {}},
                 {ms.viewer, "--html", {}}},
                read);
  if (o.html && !built_with_viewer())
    throw Error("--html: this meshsal was built without the web viewer (web/node_modules was missing at build "
                "time: run tools/setup.sh, then build again)");
  for (const std::string& in : inputs) {
    struct stat st;
    if (::stat(in.c_str(), &st) == 0) ms.input_ids.insert({st.st_dev, st.st_ino});
  }
  return ms;
}

// What runs killed mid-write left: temporaries of the outputs a batch writes (on one rank:
// the others' scan does not need it).
void remove_batch_temporaries(const std::string& out_dir) {
  const auto batch_output = [](const std::string& base) {
    for (const char* end : {"_saliency.ply", "_view.png", "_view.html", "_simplified.obj", "_lod.glb", ".state"})
      if (base.size() > std::strlen(end) && base.compare(base.size() - std::strlen(end), std::string::npos, end) == 0)
        return true;
    return false;
  };
  if (meshsal::cli::mpi_world().rank == 0) {
    remove_stale_temporaries(out_dir, batch_output);
    remove_stale_temporaries(out_dir + "/.meshsal-batch", batch_output);
  }
}

// Each model: not read (refused, not a regular file), up to date (skipped) or computed.
// Under MPI every rank makes the same choices here, before any rank writes (the barrier).
struct Choices {
  std::string options;  // options_line
  std::vector<std::string> refused, not_read, skip_record;  // per model ("": not so)
  std::vector<size_t> to_compute;                            // model indices, in order
};

Choices choose_models(const Options& o, const Models& ms) {
  Choices ch;
  const size_t n = ms.inputs.size();
  ch.options = options_line(o);
  ch.refused.resize(n), ch.not_read.resize(n), ch.skip_record.resize(n);
  for (size_t i = 0; i < n; ++i) {
    ch.refused[i] = output_is_an_input(ms.outs[i], ms.input_ids);
    if (ch.refused[i].empty()) ch.not_read[i] = not_read_reason(ms.inputs[i]);
    if (!ch.refused[i].empty() || !ch.not_read[i].empty()) continue;
    ModelState saved;
    if (!o.force && load_state(state_path(o.out_dir, ms.names[i]), &saved)) {
      try {
        if (up_to_date(saved, fingerprint(ms.inputs[i]), ch.options, ms.outs[i].all())) ch.skip_record[i] = saved.record;
      } catch (const Error&) {
        // unreadable now: it is loaded, and fails with the loader's message
      }
    }
    if (ch.skip_record[i].empty()) ch.to_compute.push_back(i);
  }
  return ch;
}

// The models' run on this rank, round by round (batch_ranks.h), and on rank 0, the writer,
// their log lines in model order, then the contact sheet, the gallery and the summary.
class BatchRun {
 public:
  // Opens the log (the writer) and routes the requests' progress and notices here.
  BatchRun(const Options& o, Plan& p, const Models& ms, const Choices& ch, int ranks, int rank)
      : o_(o), p_(p), ms_(ms), ch_(ch), ranks_(ranks), rank_(rank), writer_(rank == 0),
        log_(writer_ ? std::make_unique<BatchLog>(ms.log_path) : nullptr),
        progress_(writer_ && !o.text.quiet && stderr_is_terminal(), ms.inputs.size()),
        has_view_(ms.inputs.size(), false), sheet_status_(ms.inputs.size()), sheet_message_(ms.inputs.size()),
        computed_by_(size_t(ranks), 0), results_(ms.inputs.size()), has_result_(ms.inputs.size(), false) {
    if (log_ && log_->torn_bytes() && !o.text.quiet)  // its lines follow on a line of their own
      std::fprintf(stderr, "note: %s: ignored a torn last line (%llu bytes) from an interrupted run\n",
                   printable(ms.log_path).c_str(), static_cast<unsigned long long>(log_->torn_bytes()));
    Request& req = p.request;
    req.saliency.progress = [this](const char* stage, double f) { progress_.stage(stage, f); };
    req.viewpoint.optimiser.progress = req.saliency.progress;
    req.saliency.notice = [this](const std::string& line) {
      if (model_notes_) model_notes_->push_back(line);
      // Under MPI rank 0 tells a model's notes with its line, in model order.
      if (ranks_ == 1 || (!model_notes_ && writer_)) tell(line);
    };
    req.viewpoint.notice = req.saliency.notice;
    // The pages' viewer first, so that each page works as soon as it is written (checked
    // with the other outputs in find_models; rewritten by each run, as the gallery is).
    if (writer_ && o.html) write_viewer_script(ms.viewer);
    t_run_.restart();
  }
  BatchRun(const BatchRun&) = delete;  // the requests' callbacks hold `this`
  BatchRun& operator=(const BatchRun&) = delete;

  // This rank's models, each round's results gathered and logged by the writer.
  void compute_all() {
    const std::vector<size_t>& to_compute = ch_.to_compute;
    // This rank's models: the (round * ranks + rank)-th to compute.
    std::vector<std::string> to_load;
    for (size_t k = size_t(rank_); k < to_compute.size(); k += size_t(ranks_)) to_load.push_back(ms_.inputs[to_compute[k]]);
    std::unique_ptr<ModelLoader> loader;  // none out of core: saliency_file reads each file
    if (!to_load.empty() && !p_.request.out_of_core.memory_limit)
      loader = std::make_unique<ModelLoader>(to_load, p_.simplifying || !p_.request.lod.empty());
    const size_t rounds = batch_rounds(to_compute.size(), ranks_);
    for (size_t round = 0; round < rounds && !interrupted_; ++round) {
      const size_t first = round * size_t(ranks_), k = first + size_t(rank_);
      log_until(to_compute[first]);  // rank 0's model is the round's first
      std::vector<ModelResult> mine;
      if (k < to_compute.size()) {
        const size_t i = to_compute[k];
        progress_.remaining(rounds - round - 1);
        progress_.model(logged_, file_name(ms_.inputs[i]));
        LoadedModel m;
        if (loader) m = loader->next();
        else m.path = ms_.inputs[i];
        mine.push_back(compute(i, m));
        if (mine.back().status == "done") progress_.computed(mine.back().seconds);
      }
      for (ModelResult& r : gather_results(mine)) {
        interrupted_ = interrupted_ || r.status == "interrupted";
        has_result_[r.index] = true;
        results_[r.index] = std::move(r);
      }
      // An interrupted round: its models' lines (the interrupted one's says so), then the
      // summary; the models after it are not logged, as in one process.
      log_until(to_compute[std::min(to_compute.size(), first + size_t(ranks_)) - 1] + 1);
    }
    if (!interrupted_) log_until(ms_.inputs.size());
  }

  // After compute_all: the log synced, the contact sheet, the gallery and the summary (the
  // writer); every rank's exit status.
  int finish() {
    progress_.clear();
    if (!writer_) return agreed_status(0);
    log_->finish();
    const bool sheet_failed = !o_.contact_sheet.empty() && !interrupted_ && !write_sheet();
    const bool gallery_failed = o_.html && !interrupted_ && !write_gallery_page();
    print_summary(sheet_failed, gallery_failed);
    if (!log_->error().empty())
      std::fprintf(stderr, "error: the log %s misses %zu line%s (the write error is above)\n",
                   printable(ms_.log_path).c_str(), log_->lost(), log_->lost() == 1 ? "" : "s");
    if (interrupted_) {
      std::fprintf(stderr, "interrupted (a new run resumes where this one stopped)\n");
      std::fflush(stderr);
      return agreed_status(interrupted_exit());
    }
    return agreed_status(failed_ || !log_->error().empty() || sheet_failed || gallery_failed ? 1 : 0);
  }

 private:
  // Each notice once per run, not once per model.
  void tell(const std::string& line) {
    if (!o_.text.quiet && told_.insert(line).second) {
      progress_.clear();
      std::fprintf(stderr, "%s\n", printable(line).c_str());
    }
  }

  void report_failure(const std::string& in, size_t i, const std::string& error) {
    sheet_status_[i] = "failed";
    sheet_message_[i] = error;
    progress_.clear();
    log_->add(failed_line(in, ms_.names[i], error));
    std::fprintf(stderr, "error: %s\n", printable(error).c_str());
  }

  // Rank 0: the log lines of the models before `end` not logged yet, in order: those not
  // computed, and the results of those computed (all of them in by then).
  void log_until(size_t end) {
    for (; writer_ && logged_ < end; ++logged_) {
      const size_t i = logged_;
      const std::string& in = ms_.inputs[i];
      if (!ch_.refused[i].empty()) {
        report_failure(in, i, ch_.refused[i]);
        failed_++;
      } else if (!ch_.not_read[i].empty()) {
        JsonObject j;
        j.text("mesh", in).text("status", "skipped").text("name", ms_.names[i]).text("reason", ch_.not_read[i]);
        progress_.clear();
        log_->add(j.str());
        if (!o_.text.quiet) std::fprintf(stderr, "note: skipped %s: %s\n", printable(in).c_str(), ch_.not_read[i].c_str());
        sheet_status_[i] = "skipped";
        sheet_message_[i] = ch_.not_read[i];
        skipped_++;
      } else if (!ch_.skip_record[i].empty()) {
        log_->add(skipped_line(ch_.skip_record[i]));
        has_view_[i] = o_.view || o_.html;
        skipped_++;
      } else if (has_result_[i]) {
        const ModelResult& r = results_[i];
        if (ranks_ > 1)
          for (const std::string& note : r.notes) tell(note);
        if (r.status == "failed") {
          report_failure(in, i, r.error);
          failed_++;
        } else {
          progress_.clear();
          log_->add(r.line);
          if (r.status == "done") {
            has_view_[i] = r.has_view;
            computed_++;
            computed_by_[size_t(r.rank)]++;
          }
        }
      }
    }
  }

  // One model on this rank: its result (the outputs and state written when done).
  ModelResult compute(size_t i, LoadedModel& m) {
    const std::string& in = ms_.inputs[i];
    ModelResult res;
    res.index = i;
    std::vector<std::string> notes;
    model_notes_ = &notes;
    std::string error = m.error;
    if (error.empty()) {
      try {
        const Timer t;
        if (ms_.inputs_in_output_folder) mark_started(state_path(o_.out_dir, ms_.names[i]));
        JsonObject j = compute_model(p_, m, ms_.names[i], ms_.outs[i], progress_);
        if (!notes.empty()) {
          std::string arr = "[";
          for (size_t k = 0; k < notes.size(); ++k) arr += (k ? ", " : "") + json_string(notes[k]);
          j.raw("notes", arr + "]");
        }
        res.line = save_record(i, j);
        res.status = "done";
        res.has_view = o_.view || o_.html;
        res.seconds = t.seconds() + m.seconds;
      } catch (const Cancelled&) {
        JsonObject j;  // Ctrl-C: this model's line says so, then the summary
        j.text("mesh", in).text("status", "interrupted").text("name", ms_.names[i]);
        res.status = "interrupted";
        res.line = j.str();
      } catch (const std::bad_alloc&) {
        error = in + ": out of memory";
      } catch (const std::exception& e) {
        error = e.what();
      }
    }
    model_notes_ = nullptr;
    if (!error.empty()) {
      res.status = "failed";
      res.error = error;
    }
    res.notes = std::move(notes);
    m.mesh = {};  // free them before the next one is read
    m.attributed = {};
    return res;
  }

  // The record that lets a later run skip model i, after its outputs are in place: its
  // input, the options, its outputs' sizes and its log line `j`, which it returns.
  std::string save_record(size_t i, const JsonObject& j) {
    ModelState state;
    state.input = fingerprint(ms_.inputs[i]);
    state.options = ch_.options;
    state.output_sizes = output_sizes(ms_.outs[i]);
    state.record = j.str();
    save_state(state_path(o_.out_dir, ms_.names[i]), state);
    return state.record;
  }

  // Every model: its picture, or a marked tile with its error (the input's path shown as
  // its name, which the label under the tile gives in full). False when it failed.
  bool write_sheet() {
    const std::vector<std::string>& inputs = ms_.inputs;
    std::vector<SheetItem> items;
    for (size_t i = 0; i < inputs.size(); ++i) {
      std::string message = sheet_message_[i];
      const std::string name = file_name(inputs[i]);
      for (size_t at = 0; !inputs[i].empty() && (at = message.find(inputs[i], at)) != std::string::npos;
           at += name.size())
        message.replace(at, inputs[i].size(), name);
      items.push_back({name, has_view_[i] ? ms_.outs[i].view : "", sheet_status_[i], message});
    }
    try {
      write_png(o_.contact_sheet, contact_sheet(items));
    } catch (const Error& e) {
      std::fprintf(stderr, "error: %s\n", printable(e.what()).c_str());
      return false;
    }
    return true;
  }

  // Every model: its thumbnail opening its page, or a marked card with its error. False
  // when it failed.
  bool write_gallery_page() {
    std::vector<GalleryItem> items;
    for (size_t i = 0; i < ms_.inputs.size(); ++i) {
      const bool shown = has_view_[i] && sheet_status_[i].empty();
      items.push_back({file_name(ms_.inputs[i]), shown ? file_name(ms_.outs[i].page) : "",
                       shown ? file_name(ms_.outs[i].view) : "", sheet_status_[i].empty() ? "done" : sheet_status_[i],
                       sheet_message_[i]});
    }
    try {
      write_gallery(ms_.gallery, items);
    } catch (const Error& e) {
      std::fprintf(stderr, "error: %s\n", printable(e.what()).c_str());
      return false;
    }
    return true;
  }

  // The run's summary: one JSON object with --json (each model's is its log line), else a
  // line and the files written, unless --quiet.
  void print_summary(bool sheet_failed, bool gallery_failed) const {
    const std::string& log_path = ms_.log_path;
    if (o_.text.json) {
      std::vector<std::string> written{log_path};
      if (!o_.contact_sheet.empty() && !sheet_failed && !interrupted_) written.push_back(o_.contact_sheet);
      if (o_.html) written.push_back(ms_.viewer);
      if (o_.html && !gallery_failed && !interrupted_) written.push_back(ms_.gallery);
      JsonObject().count("models", ms_.inputs.size()).count("computed", computed_).count("skipped", skipped_)
          .count("failed", failed_).flag("interrupted", interrupted_).count("ranks", uint64_t(ranks_))
          .count("threads_per_rank", meshsal::resolve_threads(p_.request.saliency.threads))
          .text("log", log_path).strings("outputs", written).number("seconds", t_run_.seconds()).print();
    } else if (!o_.text.quiet) {
      std::string on_ranks;  // how the computed models were shared (none with one process)
      for (int r = 0; ranks_ > 1 && r < ranks_; ++r)
        on_ranks += (r ? ", " : (" on " + std::to_string(ranks_) + " ranks (computed: ")) +
                    std::to_string(computed_by_[size_t(r)]) + (r + 1 == ranks_ ? ")" : "");
      std::printf("batch: %zu models: %zu computed, %zu skipped, %zu failed%s in %.3f s%s; log %s\n", ms_.inputs.size(),
                  computed_, skipped_, failed_, interrupted_ ? ", then interrupted" : "", t_run_.seconds(),
                  on_ranks.c_str(), printable(log_path).c_str());
      if (!o_.contact_sheet.empty() && !sheet_failed) std::printf("wrote  %s\n", printable(o_.contact_sheet).c_str());
      if (o_.html) std::printf("wrote  %s\n", printable(ms_.viewer).c_str());
      if (o_.html && !gallery_failed && !interrupted_) std::printf("wrote  %s\n", printable(ms_.gallery).c_str());
      std::fflush(stdout);
    }
  }

  const Options& o_;
  Plan& p_;
  const Models& ms_;
  const Choices& ch_;
  const int ranks_, rank_;
  const bool writer_;  // the log, the messages, the summary, the sheet
  std::unique_ptr<BatchLog> log_;
  BatchProgress progress_;
  std::set<std::string> told_;
  std::vector<std::string>* model_notes_ = nullptr;  // the running model's notices
  std::vector<bool> has_view_;                        // for the contact sheet
  std::vector<std::string> sheet_status_, sheet_message_;  // the others'
  Timer t_run_;
  size_t computed_ = 0, skipped_ = 0, failed_ = 0;
  std::vector<size_t> computed_by_;
  bool interrupted_ = false;
  std::vector<ModelResult> results_;  // the writer's: of the models computed, until logged
  std::vector<bool> has_result_;
  size_t logged_ = 0;
};

int run(Options o) {
  check_options(o);
  Plan p = make_plan(o);
  const Models ms = find_models(o, p);
  remove_batch_temporaries(o.out_dir);
  const Choices ch = choose_models(o, ms);
  const meshsal::cli::MpiWorld& world = meshsal::cli::mpi_world();
  const int ranks = world.active ? world.size : 1, rank = world.active ? world.rank : 0;
  meshsal::cli::mpi_begin_work();  // the first collective: a rank that failed before stops all alike
  check_same_models(ms.inputs, ch.options, ch.to_compute);
  meshsal::cli::mpi_barrier();
  BatchRun batch(o, p, ms, ch, ranks, rank);
  batch.compute_all();
  return batch.finish();
}

RunFn setup(CLI::App& sub) {
  auto o = std::make_shared<Options>();
  sub.footer(
      "Compute the saliency of many models in one process (one Vulkan device and its compiled\n"
      "pipelines for the whole run; the next model is read while the current one computes).\n"
      "Per model, in DIR: NAME_saliency.ply (as `meshsal saliency`), with --view NAME_view.png\n"
      "(the best view, as `meshsal viewpoint -o`), with --html NAME_view.html (as `meshsal view`)\n"
      "and the gallery DIR/index.html (the pages' viewer once beside it: DIR/meshsal-viewer.js),\n"
      "with --lod NAME_lod.glb (as `simplify --lod`), and with\n"
      "--simplify and/or --target-error NAME_simplified.obj: the same file\n"
      "`meshsal simplify IN -o OUT.obj` writes with the same\n"
      "options (--ratio R or --target-faces N as --simplify, --target-error, --lock-border,\n"
      "--weights, --weight-floor), texture coordinates and normals (OBJ vt/vn, PLY properties)\n"
      "carried along and UV seams kept closed. NAME is the file name without its extension (the\n"
      "whole name, or a _2.. suffix, where two inputs share it). DIR/batch.jsonl (or --log)\n"
      "gets one JSON object per model, appended as each ends (earlier runs' lines stay): its\n"
      "input, status (done, skipped, failed), outputs, counts, seconds per stage, saliency\n"
      "statistics as `saliency --json` prints them, the best view, the device; or `error` with\n"
      "the message. A last line an interrupted run left torn (not JSON) is noted and stays; the\n"
      "new lines start on a line of their own. Names that are not UTF-8 appear with \\udcXX\n"
      "escapes for their odd bytes (Python: os.fsencode(json.loads(line)['mesh'])).\n"
      "Resume: DIR/.meshsal-batch/NAME.state records what made each model's outputs; a model is\n"
      "skipped when its input (size, time and a content hash) and these options are the same and\n"
      "its outputs are in place (its line repeats the earlier numbers); otherwise it is computed\n"
      "again (--force: always), as it is when its state file is not one batch wrote (not a\n"
      "regular file, over 1 MiB, torn or edited: nothing of it goes into the log). Refused before\n"
      "any work (usage error, exit status 2): --log, --contact-sheet or the gallery\n"
      "DIR/index.html being the same file as another of them or as a model's output or state file\n"
      "(also through a link); --html, --view or --contact-sheet with --memory-limit. DIR may be\n"
      "an input folder too: the outputs earlier runs wrote there (NAME_saliency.ply,\n"
      "NAME_simplified.obj of a model with a state file) are not taken as inputs. Only regular\n"
      "files are read: a named pipe or a device among the inputs is skipped with its reason. A\n"
      "failing model is logged and the others go on; the exit status is 1 when any failed or a\n"
      "log line could not be written. --contact-sheet shows every model: a thumbnail, or a grey\n"
      "tile with a red cross, \"failed\" and the error (\"skipped\" and the reason for an input\n"
      "not read). Inputs: files, folders (the mesh files inside with a mesh extension: .obj .ply\n"
      ".off .stl .gltf .glb, optionally .gz; sorted by name), quoted globs ('scans/*.ply'), @LIST\n"
      "or --list LIST (a regular file or - for standard input: one item per line, # comments,\n"
      "relative items taken from the list's folder; at most 64 MiB, 4096 bytes a line, 1,000,000\n"
      "items).\n"
      "MPI: `mpirun -np N meshsal batch ...` (a build with MPI) shares the models to compute\n"
      "over the N ranks (the k-th to rank k % N); rank 0 writes the one log, in model order,\n"
      "and the summary; resume as above. Every rank needs the same command and sees the same\n"
      "folders. A rank that fails (outside a model) ends every rank with its message and status.");
  sub.add_option("inputs", o->inputs, "Mesh files, folders, globs or @LIST files");
  sub.add_option("--list", o->list_file, "A file listing the inputs, one per line");
  sub.add_option("-o,--output", o->out_dir, "Output folder (made if missing)")->required();
  sub.add_option("--log", o->log, "The JSON Lines log (default DIR/batch.jsonl)");
  sub.add_flag("--view", o->view, "Also write the best-view picture NAME_view.png");
  sub.add_option("--lod", o->lod,
                 "Also write NAME_lod.glb, the file `meshsal simplify IN -o NAME_lod.glb --lod LIST` writes: the\n"
                 "input as LOD0 and each level (ratios of the faces, or face counts), linked by MSFT_lod")
      ->check(lod_list());
  sub.add_flag("--html", o->html,
               "Also write NAME_view.html per model (the page `meshsal view` writes: the model in the browser,\n"
               "from its best view) and DIR/index.html, a gallery of every model's thumbnail (NAME_view.png,\n"
               "implied) opening its page, failed models marked; not with --memory-limit");
  sub.add_option("--simplify", o->simplify,
                 "Also write NAME_simplified.obj with saliency weights: a ratio of the faces in (0, 1], "
                 "or a face count above 1 (as simplify --ratio / --target-faces)")->check(finite_in(0, 1e12, true));
  sub.add_option("--target-error", o->target_error,
                 "Also (or with --simplify) an error bound E in % of the bounding-box diagonal for "
                 "NAME_simplified.obj, as simplify --target-error: stop where every further collapse would "
                 "move the surface more than that (alone: simplify as far as it allows)")
      ->check(finite_in(0, 100, true));
  sub.add_flag("--lock-border", o->lock_border,
               "Simplified mesh: keep the vertices of open borders exactly in place (as simplify --lock-border)");
  add_weight_options(sub, o->text);
  sub.add_option("--contact-sheet", o->contact_sheet,
                 "One PNG with a tile per model: its best-view picture as a thumbnail, or a failed one "
                 "marked with its error; the name under it (implies --view)");
  add_memory_options(sub, o->text,
                     "Compute each model's saliency out of core under this peak resident memory (e.g. "
                     "700M, 2G), as `saliency --memory-limit` does; no --view, --html, --contact-sheet or --target-error.");
  sub.add_flag("--force", o->force, "Recompute models whose outputs are up to date");
  add_saliency_options(sub, o->text);
  add_picture_options(sub, o->text, "side of the best-view picture in pixels");
  add_view_options(sub, o->text);
  sub.add_flag("-q,--quiet", o->text.quiet, "Print nothing but errors (no progress, notes or summary)");
  sub.add_flag("--json", o->text.json,
               "Print the run's summary as one JSON object on stdout (models, computed, skipped, failed, log, "
               "outputs); each model's is its line in the log");
  return [o, &sub] {
    o->weight_floor_given = sub.get_option("--weight-floor")->count() > 0;
    return run(*o);
  };
}

const bool registered = register_command({"batch", "Saliency (and best views, simplified meshes) of many models", 15, setup, true});

}  // namespace
}  // namespace meshsal::cli
