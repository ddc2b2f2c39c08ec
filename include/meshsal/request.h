// meshsal public interface: one request: what a run asks for, from any front end.
// Part of meshsal.h (which includes every part); the conventions at the top of
// meshsal.h hold for every function here.
#pragma once
#include <functional>
#include <string>
#include <vector>

#include "meshsal/io.h"
#include "meshsal/mesh.h"
#include "meshsal/saliency.h"
#include "meshsal/simplify.h"
#include "meshsal/tiles.h"
#include "meshsal/view.h"

namespace meshsal {

// ------------------------------------------------------------------------------------------
// One request: what a run asks for, from any front end

// Options of a request that do not combine (e.g. --lod with --memory-limit): raised by
// check_request() before any work. An Error; the command-line tool exits 2 for it, as for
// any usage error.
struct RequestError : Error {
  using Error::Error;
};

// What one run asks for: an input, how its S is had, and what to make of it. Every front
// end fills one and calls run_request(): `meshsal saliency`, `simplify`, `view`, `render`,
// `viewpoint`, each model of `batch`, and Python. The defaults below are every command's
// defaults, and check_request() holds the rules for what combines, so that a new option or
// output lands once for all of them.
struct Request {
  // The input: the mesh file `input`; or, when `mesh` is given (not owned; it must outlive
  // the call), that mesh as read plainly (LoadOptions::attributes off) and `input` only
  // names it (messages, pages, the check that no output replaces it). `attributed`: the
  // same file read with attributes, when the caller has it (batch reads ahead).
  std::string input;
  const Mesh* mesh = nullptr;
  const Mesh* attributed = nullptr;
  LoadOptions load;  // limits of reading (attributes is decided by the outputs: below)

  // S: computed with `saliency` (its defaults are every command's), or read back from
  // `saliency_from` (a PLY or glTF that keeps S: load_saliency); with saliency_from_input,
  // from the input itself when it holds S (a saliency PLY given to `render` or `view`).
  // Every front end's default backend is Auto (a GPU when there is one), not the CPU that
  // a bare SaliencyOptions names.
  SaliencyOptions saliency = [] {
    SaliencyOptions o;
    o.backend = Backend::Auto;
    return o;
  }();
  std::string saliency_from;
  bool saliency_from_input = false;
  // Or S given by the caller (not owned): one value per vertex of `mesh`, which must then
  // be given too (Python's saliency= argument).
  const std::vector<double>* saliency_values = nullptr;
  // What the views and pictures show (S, or |H| for the paper's comparison).
  Score score = Score::Saliency;

  // The outputs; "" = not made. Each is checked before any work (check_outputs: the
  // extension its writer takes, writable, distinct, never an input) with its side files.
  // saliency_output: the mesh with S, in any format (mesh_format: PLY and glTF keep the
  // value, OBJ and OFF its colours, STL is refused); a PLY holds the positions and faces
  // as read (no attributes: SPEC section 4), the others carry the input's attributes and
  // materials. dump_scales: also the curvature and raw maps (PLY, glTF).
  std::string saliency_output;
  bool dump_scales = false;
  // simplified_output: the mesh simplified toward `simplify`'s target (faces, ratio or
  // error), its attributes and materials carried, S carried as a PLY's `quality` or a
  // glTF's _SALIENCY where the format keeps it. simplify.tiles > 1: simplify_mesh_tiled.
  std::string simplified_output;
  SimplifyOptions simplify;
  // lod_output: a chain of levels of detail, `lod` (parse_lod_levels), S computed once and
  // carried (write_lod: one glTF with MSFT_lod, or a file per level).
  std::string lod_output;
  std::vector<SimplifyOptions> lod;
  // Make the simplified mesh (with a target in `simplify`) and the levels (with `lod`) even
  // where no output file is named: they come back in the result (Python).
  bool simplify_in_memory = false;
  // The weights of simplified_output and lod_output: a named weighting, its parameters in
  // weight_options (weight_preset(weighting) unless the caller changed them).
  Weighting weighting = kDefaultWeighting;
  SaliencyWeightOptions weight_options = weight_preset(kDefaultWeighting);
  // Or the weights W themselves, one per vertex of `mesh` (not owned): no S is had for
  // them (Python's weights= array).
  const std::vector<double>* vertex_weights = nullptr;
  // memory_limit > 0: the mesh is never held whole (saliency_file, simplify_file; PLY
  // outputs only, no views).
  OutOfCoreOptions out_of_core;

  // The view: searched (best_viewpoint with `viewpoint`) when find_view, else `view`.
  // page_output: the viewer page (write_view_page) from the best view, which it needs.
  // picture_output: the picture (PNG) of that view, titled and with its colour bar (`grey`:
  // shaded only; `compare`: two more meshes beside it, PLAIN and SALIENT, coloured by their
  // distance to the input). map_output: the view map (with viewpoint.views directions,
  // 2000 when 0), map_width pixels wide.
  bool find_view = false;
  ViewpointOptions viewpoint = [] {
    ViewpointOptions o;
    o.backend = Backend::Auto;
    return o;
  }();
  ViewAngles view;
  std::string page_output;
  ViewPageOptions page;
  std::string picture_output;
  RenderStyle style;
  bool grey = false;
  std::vector<std::string> compare;
  std::string map_output;
  int map_width = 720;

  // What messages call the outputs: "-o" (the command line's option), "the output" (Python).
  std::string output_option = "-o";

  // Called once the input is read (before S; out of core, before the file is streamed):
  // where processes that share the run meet (the command line's MPI ranks). May be empty.
  std::function<void()> on_read;
};

// What a request made.
struct RequestResult {
  Mesh mesh;                       // the input as read (plainly, or with attributes when only those were needed)
  LoadReport load;                 // what reading it left out (LoadReport::unread), STL welding
  double load_seconds = 0;
  // S on a GPU from a PLY: seconds spent uploading the mesh on a second thread while it was
  // read, most of them hidden by the read (what was not is saliency's "device warm-up"
  // stage), so not among the stages; 0 where nothing was uploaded ahead.
  double upload_while_reading = 0;
  SaliencyResult saliency;         // S (computed; read back: only saliency and is_point filled)
  std::string saliency_source;     // "computed" or the file S was read from
  std::vector<double> score;       // what the views showed (S, or |H|), per vertex
  OutOfCoreReport out_of_core;     // saliency_output under a memory limit
  // simplified_output: its mesh (empty out of core), report, the weights' alpha and the
  // device that computed the S they came from ("" when S was read).
  Mesh simplified;
  SimplifyReport simplify;
  double alpha = 0;
  std::string weights_device;
  double weights_seconds = 0;  // having S (computed or read) and the weights from it
  OutOfCoreSimplifyReport simplify_out_of_core;
  std::vector<LodLevel> lod;       // lod_output's levels
  std::vector<std::string> lod_files;  // the files they went to (one GLB, or one per level)
  Viewpoint viewpoint;             // find_view's result
  ViewAngles view;                 // the view the picture shows
  ViewPageReport page;
  int picture_width = 0, picture_height = 0;
  double visible_score = 0, visible_total = 0;  // the picture's view: U and the score's sum
  // Every file written, in the order written (side files after their main file), and the
  // notes a front end shows once each: what an output cannot hold (mesh_output_note), a
  // face target missed, S read from the input.
  std::vector<std::string> outputs;
  std::vector<std::string> notes;
  // Wall time of each step that ran, in order: "read", "saliency output", "views",
  // "simplify", "levels of detail" (out of core: "saliency output", "simplify").
  std::vector<StageTime> steps;
  double seconds = 0;
};

// Throws RequestError when the request's options do not combine (naming them as the
// command-line options do: "--lod runs in memory, in one piece: not with --tiles or
// --memory-limit"), or Error when one is out of range or an output cannot be written
// (check_outputs); before any file is read.
void check_request(const Request& request);

// Runs the request: check_request, then reads the input (once plainly and once with
// attributes where outputs need both, as each command always has), has S (computed or
// read back, once for every output), makes every output asked for and writes it. Progress,
// notices and cancellation go through request.saliency (progress, notice, cancel) and
// request.viewpoint. Throws Error (RequestError for the combinations) or Cancelled.
RequestResult run_request(const Request& request);

}  // namespace meshsal
