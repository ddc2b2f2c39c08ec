// meshsal: run_request, every front end's pipeline: check, read, S once, then each output
// (the saliency mesh, the views, the simplified mesh, the levels of detail).
#include <algorithm>
#include <memory>
#include <string>
#include <vector>

#include "api/gpu_backend.h"
#include "api/read_upload.h"
#include "api/request_parts.h"
#include "core/timer.h"
#include "saliency/saliency.h"
#include "meshsal/meshsal.h"

namespace meshsal {
namespace {

// What a request implies beyond what it says, for every front end alike: tiled
// simplification takes its weights from the paper's S computed in the same tiles (the same
// map, a tile at a time), unless the request names the saliency's tiles itself; the other
// models are had whole.
Request with_implied_options(const Request& given) {
  Request r = given;
  if (r.simplify.tiles > 1 && r.saliency.tiles == 0 && r.saliency.model == Model::Lee2005)
    r.saliency.tiles = std::min<unsigned>(r.simplify.tiles, kMaxTiles);
  return r;
}

bool weighted_simplification(const Request& r) {
  return r.weighting != Weighting::None && (!r.simplified_output.empty() || !r.lod_output.empty() || r.simplify_in_memory);
}

// Whether the request has a view found or drawn (the page, the picture, the view map).
bool makes_views(const Request& r) {
  return !r.page_output.empty() || !r.picture_output.empty() || !r.map_output.empty() || r.find_view;
}

// Whether the request computes S of the paper's model on one machine from a file it reads:
// what warm_up_saliency prepares the device for (S read back, given, or not needed by any
// output, another model, tiles or ranks: nothing to prepare).
bool warms_up_device(const Request& r) {
  const bool needs_s =
      !r.saliency_output.empty() || (makes_views(r) && r.score == Score::Saliency) || weighted_simplification(r);
  const SaliencyOptions& o = r.saliency;
  return needs_s && !r.mesh && r.saliency_from.empty() && !r.saliency_values && o.backend != Backend::Cpu &&
         o.model == Model::Lee2005 && o.tiles == 0 && !o.exchange && !o.session;
}

}  // namespace

bool writes_files(const Request& r) {
  const TileExchange* x = r.saliency.exchange ? r.saliency.exchange : r.simplify.exchange;
  return !x || x->rank() == 0;
}

std::string file_name_of(const std::string& path) {
  const size_t slash = path.find_last_of('/');
  return slash == std::string::npos ? path : path.substr(slash + 1);
}

void add_note(RequestRun& run, const std::string& note) {
  if (note.empty()) return;
  for (const std::string& n : run.result.notes)
    if (n == note) return;
  run.result.notes.push_back(note);
  if (run.request.saliency.notice) run.request.saliency.notice("note: " + note);
}

std::vector<std::string> check_side_files(RequestRun& run, const std::string& path, const Mesh& mesh) {
  // The side files (an OBJ's .mtl and textures) get the output check the main file had.
  const std::vector<std::string> side = mesh_side_files(path, mesh);
  if (!side.empty()) {
    std::vector<OutputFile> files;
    for (const std::string& f : side) files.push_back({f, run.request.output_option, {}});
    std::vector<std::string> inputs{run.request.input, run.request.saliency_from, path};
    check_outputs(files, inputs);
  }
  return side;
}

void write_request_mesh(RequestRun& run, const std::string& path, const Mesh& mesh, const std::vector<double>& saliency) {
  const std::vector<std::string> side = check_side_files(run, path, mesh);
  write_mesh(path, mesh, saliency);
  run.result.outputs.push_back(path);
  run.result.outputs.insert(run.result.outputs.end(), side.begin(), side.end());
  add_note(run, mesh_output_note(path, mesh, !saliency.empty()));
}

double RequestRun::timer_seconds() const { return timer.seconds(); }

RequestResult run_request(const Request& given) {
  check_request(given);
  const Request r = with_implied_options(given);
  RequestResult result;
  RequestRun run{r, result};
  // Runs one step of the request, timed into result.steps.
  const auto step = [&](const char* name, const auto& body) {
    const Timer t;
    body();
    result.steps.push_back({name, t.seconds()});
  };
  if (r.out_of_core.memory_limit > 0) {
    // The mesh is never held whole: the library streams the file through tiles on disk.
    if (r.on_read) r.on_read();
    // Both outputs: simplify_file writes S from the tiles that weigh it (S once).
    if (!r.saliency_output.empty() && !r.simplified_output.empty()) {
      step("simplify", [&] { make_simplified(run); });
      result.out_of_core = result.simplify_out_of_core.saliency;
      if (writes_files(r)) result.outputs.insert(result.outputs.begin(), r.saliency_output);
      result.seconds = run.timer_seconds();
      return result;
    }
    if (!r.saliency_output.empty())
      step("saliency output", [&] {
        OutOfCoreOptions o = r.out_of_core;
        o.dump_scales = r.dump_scales;
        result.out_of_core = saliency_file(r.input, r.saliency_output, r.saliency, o);
        if (writes_files(r)) result.outputs.push_back(r.saliency_output);
      });
    if (!r.simplified_output.empty()) step("simplify", [&] { make_simplified(run); });
    result.seconds = run.timer_seconds();
    return result;
  }
  // S to compute on a GPU from a file still to read: the device opened, the pipelines
  // compiled and the probes run on a thread while the file is read (a GPU run's
  // once-per-process costs, about 0.6 s on the H200: docs/benchmarks.md), and the mesh
  // uploaded as it is read, so that the computation starts at once (read_upload.h). (A
  // mesh given in memory has nothing to overlap with.) The device it resolved (Auto's
  // pick) is the run's, so the run lists the devices no second time.
  std::unique_ptr<ReadUpload> upload;
  if (warms_up_device(r)) {
    SaliencyOptions so = r.saliency;
    so.smoothed = weighted_simplification(r);
    upload = std::make_unique<ReadUpload>(so);
    run.read_observer = upload.get();
  }
  step("read", [&] { read_input(run); });  // a throw ends the upload (its destructor)
  run.read_observer = nullptr;
  SaliencyOptions warmed;
  if (upload && upload->join(warmed, run.warm_up_wait, result.upload_while_reading)) {
    run.saliency.backend = warmed.backend;
    run.saliency.device = warmed.device;
  }
  // S read back from the input itself: nothing uploaded ahead is taken; freed now.
  if (r.saliency_from_input && run.input_has_saliency) upload.reset();
  if (r.on_read) r.on_read();
  // Where S is computed on the plain mesh for its own outputs and the simplifier weighs by
  // it too, it is computed once with its Sm.
  if (run.plain && weighted_simplification(r) && r.saliency_from.empty() && !r.saliency_values &&
      (!r.saliency_output.empty() || !r.picture_output.empty() || !r.page_output.empty() || r.find_view))
    plain_saliency(run, true);
  if (!r.saliency_output.empty())
    step("saliency output", [&] {
      if (writes_files(r)) write_saliency_output(run);
      else plain_saliency(run, false);  // the ranks compute together; rank 0 writes
    });
  if (makes_views(r)) step("views", [&] { make_views(run); });
  if (!r.simplified_output.empty() || (r.simplify_in_memory && r.lod.empty())) step("simplify", [&] { make_simplified(run); });
  if (!r.lod_output.empty() || (r.simplify_in_memory && !r.lod.empty())) step("levels of detail", [&] { make_lod(run); });
  if (result.saliency.saliency.empty() && run.has_plain_s) result.saliency = run.plain_s;
  if (run.plain == &run.plain_read) result.mesh = std::move(run.plain_read);
  else if (run.attributed == &run.attributed_read) result.mesh = std::move(run.attributed_read);
  result.seconds = run.timer_seconds();
  return result;
}

}  // namespace meshsal
