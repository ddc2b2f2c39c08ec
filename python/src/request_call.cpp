#include "request_call.h"

#include <cstring>
#include <string>
#include <utility>

#include "arg_values.h"

namespace meshsal_py {

// run_request, its refusals (RequestError) in this module's argument names.
meshsal::RequestResult run_in_python_terms(const meshsal::Request& request) {
  try {
    return meshsal::run_request(request);
  } catch (const meshsal::RequestError& e) {
    std::string m = e.what();
    for (const auto& [flag, arg] : {std::pair{"--target-faces N", "target_faces"}, std::pair{"--ratio R", "ratio"},
                                    std::pair{"--target-error E", "target_error"}, std::pair{"--target-faces", "target_faces"},
                                    std::pair{"--ratio", "ratio"}, std::pair{"--target-error", "target_error"},
                                    std::pair{"--lod", "lod"}, std::pair{"--memory-limit", "memory_limit"},
                                    std::pair{"--tiles", "tiles"}, std::pair{"--saliency-from", "saliency_from"},
                                    std::pair{"-o OUT.ply", "an output name ending in .ply"}})
      for (size_t at = m.find(flag); at != std::string::npos; at = m.find(flag, at)) m.replace(at, std::strlen(flag), arg);
    throw py::value_error(m);
  }
}

std::vector<meshsal::SimplifyOptions> lod_levels(const py::object& lod) {
  if (py::isinstance<py::str>(lod)) return meshsal::parse_lod_levels(lod.cast<std::string>());
  const std::vector<py::object> items =
      sequence_items(lod, "lod", "a list of ratios (float) and face counts (int), or a str such as '0.5,0.2'", meshsal::kMaxLodLevels);
  if (items.empty() || items.size() > meshsal::kMaxLodLevels)
    throw py::value_error("lod must list 1 to " + std::to_string(meshsal::kMaxLodLevels) + " levels");
  std::vector<meshsal::SimplifyOptions> levels;
  for (const py::object& item : items) {
    meshsal::SimplifyOptions o;
    // An integer (numpy's too) is a face count; anything else must be a real ratio.
    if (is_integer(item)) {
      o.target_faces = size_t(integer_arg(item, "lod face counts", 1, 4000000000LL));
    } else {
      o.ratio = number_arg(item, "lod items");
      if (!(o.ratio > 0 && o.ratio < 1)) throw py::value_error("lod ratios must be in (0, 1), got " + std::string(py::str(item)));
    }
    levels.push_back(o);
  }
  return levels;
}

}  // namespace meshsal_py
