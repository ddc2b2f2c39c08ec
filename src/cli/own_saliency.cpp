#include "own_saliency.h"

#include <cstdio>

#include "json_string.h"

namespace meshsal_cli {

std::string saliency_source_file(const std::string& input, const meshsal::VertexProperties& props,
                                 const std::string& saliency_from, bool saliency_score) {
  if (!saliency_from.empty() || !saliency_score) return saliency_from;
  if (!props.count("quality")) return "";
  std::fprintf(stderr, "%s: using its own saliency (per-vertex quality, as `meshsal saliency` writes it), "
                       "not computing it again\n", printable(input).c_str());
  return input;
}

}  // namespace meshsal_cli
