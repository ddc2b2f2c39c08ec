// meshsal: a chain of levels of detail in one call (simplify_lod in meshsal.h). The
// saliency is computed once on the input and carried down the chain as a vertex attribute
// (interpolated along each collapse, as every attribute is); each level is simplified from
// the one before, which measured better than simplifying each from the input (README,
// Levels of detail: 8-12% lower RMS at 20% and 5% on bunny, armadillo and igea).
#include <cctype>
#include <cerrno>
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

#include "core/cancel.h"
#include "core/number_text.h"
#include "meshsal/meshsal.h"
#include "simplify/simplify.h"

namespace meshsal {
namespace {

// The attribute that carries S from level to level: a name no file gives.
const char* const kCarriedSaliency = "\x01meshsal lod saliency";

// One kind of level throughout (a ratio's faces and a count compare only once the mesh is
// read), each fewer than the one before, at most kMaxLodLevels: what parse_lod_levels reads and every
// chain simplify_lod takes, so that a bad list fails before the input is read.
void check_lod_levels(const std::vector<SimplifyOptions>& levels) {
  if (levels.empty()) throw Error("lod: no level given");
  if (levels.size() > kMaxLodLevels)
    throw Error("lod: at most " + std::to_string(kMaxLodLevels) + " levels, got " + std::to_string(levels.size()));
  const auto text = [](const SimplifyOptions& o) {
    return o.target_faces ? std::to_string(o.target_faces) : number_text(o.ratio);
  };
  for (size_t i = 0; i < levels.size(); ++i) {
    const SimplifyOptions& o = levels[i];
    if (o.target_error != 0) throw Error("lod: a level takes a face count or a ratio, not a target error");
    if ((o.target_faces > 0) == (o.ratio != 0))
      throw Error("lod: level " + std::to_string(i + 1) + " needs a face count or a ratio (not both)");
    if (o.ratio != 0 && !(o.ratio > 0 && o.ratio < 1))
      throw Error("lod: ratios must be in (0, 1), got " + number_text(o.ratio));
    if (i == 0) continue;
    const SimplifyOptions& before = levels[i - 1];
    if ((o.target_faces > 0) != (before.target_faces > 0))
      throw Error("lod: give ratios (e.g. 0.5,0.2) or face counts (e.g. 20000,5000), not both: level " +
                  std::to_string(i) + " is " + text(before) + ", level " + std::to_string(i + 1) + " " + text(o));
    const bool same = o.target_faces ? o.target_faces == before.target_faces : o.ratio == before.ratio;
    const bool fewer = o.target_faces ? o.target_faces < before.target_faces : o.ratio < before.ratio;
    if (same)
      throw Error("lod: level " + std::to_string(i + 1) + " repeats level " + std::to_string(i) + " (" + text(o) +
                  "): each level has fewer faces than the one before");
    if (!fewer)
      throw Error("lod: level " + std::to_string(i + 1) + " (" + text(o) + ") is not below level " +
                  std::to_string(i) + " (" + text(before) + "): list the levels from the most faces to the fewest");
  }
}

}  // namespace

std::vector<SimplifyOptions> parse_lod_levels(const std::string& text) {
  std::vector<SimplifyOptions> levels;
  const std::string usage =
      "lod must be a comma-separated list of ratios in (0, 1) or of face counts >= 1, got '" + text + "'";
  if (text.empty() || text.back() == ',' || text.size() > 1000) throw Error(usage);  // getline drops a last empty item
  std::stringstream ss(text);
  std::string item;
  while (std::getline(ss, item, ',')) {
    SimplifyOptions o;
    char* end = nullptr;
    // Decimal text only: strtod would read hex, inf and nan, strtoll a sign or spaces.
    const bool decimal = !item.empty() && item.find_first_not_of("0123456789.eE+-") == std::string::npos &&
                         (std::isdigit(static_cast<unsigned char>(item[0])) || item[0] == '.');
    if (!decimal) throw Error(usage);
    if (item.find_first_of(".eE") != std::string::npos) {
      o.ratio = std::strtod(item.c_str(), &end);
      if (*end != '\0' || !(o.ratio > 0 && o.ratio < 1)) throw Error(usage);
    } else {
      errno = 0;
      const long long n = std::strtoll(item.c_str(), &end, 10);
      if (*end != '\0' || errno == ERANGE || n < 1 || n > 4000000000LL) throw Error(usage);
      o.target_faces = size_t(n);
    }
    levels.push_back(o);
  }
  check_lod_levels(levels);
  return levels;
}

std::vector<LodLevel> simplify_lod(const Mesh& mesh, const std::vector<SimplifyOptions>& levels,
                                   const std::optional<SaliencyWeightOptions>& weight_options,
                                   const SaliencyOptions& saliency_options, const std::vector<double>& saliency) {
  const CancelScope cancel(saliency_options.cancel);
  check_lod_levels(levels);
  // Every level's face target: a ratio's of the input's faces (none left is an error, as
  // for simplify_mesh); a count may be at or above the faces of the level it starts from,
  // which then stays as it is (simplify_keeps_mesh), as simplify_mesh leaves a mesh.
  std::vector<size_t> targets;
  for (const SimplifyOptions& l : levels)
    targets.push_back(l.target_faces ? l.target_faces : resolve_target_faces(l, mesh.triangle_count()));
  Mesh current = mesh;
  std::vector<double> s;
  if (weight_options) {
    if (!saliency.empty()) {
      if (saliency.size() != mesh.vertex_count())
        throw Error("saliency has " + std::to_string(saliency.size()) + " values, the mesh has " +
                    std::to_string(mesh.vertex_count()) + " vertices");
      s = saliency;
    } else {
      SaliencyOptions so = saliency_options;
      so.raw_maps = false;  // only S is carried down the chain
      s = compute_saliency(mesh, so).saliency;
    }
  }
  std::vector<LodLevel> out;
  for (size_t i = 0; i < levels.size(); ++i) {
    SimplifyOptions o = levels[i];
    o.target_faces = targets[i];
    o.ratio = 0;
    LodLevel level;
    if (simplify_keeps_mesh(o, current.triangle_count())) {
      Simplified r = simplify_mesh(current, o);  // unchanged, as plain simplify
      level.mesh = std::move(r.mesh);
      level.report = std::move(r.report);
      level.saliency = s;
    } else if (weight_options) {
      // This level's weights from S on the mesh it starts from (smoothed there, as
      // --saliency-from does), S carried to its output.
      const SimplificationWeights w = simplification_weights(current, *weight_options, saliency_options, s);
      set_vertex_attribute(current, kCarriedSaliency, s);
      Simplified r = simplify_mesh(current, o, w.weights);
      level.mesh = std::move(r.mesh);
      level.report = std::move(r.report);
      level.saliency = take_vertex_attribute(level.mesh, kCarriedSaliency);
      take_vertex_attribute(current, kCarriedSaliency);
      s = level.saliency;
    } else {
      Simplified r = simplify_mesh(current, o);
      level.mesh = std::move(r.mesh);
      level.report = std::move(r.report);
    }
    current = level.mesh;
    out.push_back(std::move(level));
  }
  return out;
}

}  // namespace meshsal
