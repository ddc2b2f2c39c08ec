// meshsal batch: the files a run writes for each model (batch_state.h says whether they are up to date).
#pragma once
#include <string>
#include <vector>

namespace meshsal_cli {

struct ModelOutputs {
  std::string saliency;    // DIR/NAME_saliency.ply
  std::string view;        // DIR/NAME_view.png, "" when not asked
  std::string simplified;  // DIR/NAME_simplified.obj, "" when not asked
  std::vector<std::string> all() const;  // those asked for
};

// One output name per input, in input order: the file name without its mesh extension
// (and .gz); where two inputs would share it, the whole file name (bunny.obj, bunny.ply);
// where they still do (same name in two folders), "_2", "_3".. in input order.
std::vector<std::string> output_names(const std::vector<std::string>& inputs);

ModelOutputs model_outputs(const std::string& dir, const std::string& name, bool view, bool simplified);

}  // namespace meshsal_cli
