// meshsal batch: the files a run writes for each model (batch_state.h says whether they are up to date).
#pragma once
#include <string>
#include <vector>

namespace meshsal::cli {

struct ModelOutputs {
  std::string saliency;    // DIR/NAME_saliency.ply
  std::string view;        // DIR/NAME_view.png, "" when not asked
  std::string simplified;  // DIR/NAME_simplified.obj (.ply out of core), "" when not asked
  std::string page;        // DIR/NAME_view.html (--html), "" when not asked
  std::string lod;         // DIR/NAME_lod.glb (--lod), "" when not asked
  std::vector<std::string> all() const;  // those asked for
};

// The last component of a path: "models/bunny.ply" -> "bunny.ply".
std::string file_name(const std::string& path);

// One output name per input, in input order: the file name without its mesh extension
// (and .gz); where two inputs would share it, the whole file name (bunny.obj, bunny.ply);
// where they still do (same name in two folders), "_2", "_3".. in input order.
std::vector<std::string> output_names(const std::vector<std::string>& inputs);

// `simplified_ply`: NAME_simplified.ply (out of core: simplify_file writes a binary PLY).
// `page`: NAME_view.html (--html, which implies the view picture).
// `lod`: NAME_lod.glb (--lod).
ModelOutputs model_outputs(const std::string& dir, const std::string& name, bool view, bool simplified,
                           bool simplified_ply = false, bool page = false, bool lod = false);

// `inputs` without the files a batch wrote into `dir` (for an input folder that is also the
// output folder, run again): a file directly in `dir` named NAME_saliency.ply,
// NAME_simplified.obj or .ply, or NAME_lod.glb (the outputs with a mesh extension) where NAME is the output name of
// another input (output_names over the inputs kept) and DIR/.meshsal-batch/NAME.state
// exists (batch_state.h: a batch made, or was making, that model's outputs there). A file
// with such a name and no state is kept: a user's own mesh (an output never replaces it).
std::vector<std::string> without_batch_outputs(const std::vector<std::string>& inputs, const std::string& dir);

}  // namespace meshsal::cli
