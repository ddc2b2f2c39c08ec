// meshsal: the pictures the CLI writes: a rendered view with its title line (mesh name, view
// angles, visible score U) and a colour bar with values.
#pragma once
#include <string>
#include <vector>

#include "meshsal/meshsal.h"
#include "view/camera.h"

namespace meshsal {

// "theta 30°  phi 10°  (y up)": the view in degrees, as --theta/--phi/--up take it.
std::string view_text(const ViewAngles& view, UpAxis up);

// U (sum of `score` over the mesh points visible from `view`, angles in the frame of `up`) and
// the sum over all points, as the pictures give them: CPU visibility at 512 px.
struct VisibleScore {
  double U = 0, total = 0;
};
VisibleScore picture_visible_score(const Mesh& mesh, const std::vector<double>& score, const ViewAngles& view,
                                   UpAxis up);

// The mesh from `view` (style.up is the up axis), coloured by `score` on style.range's scale
// (nullptr: grey, no bar), titled
//   NAME   theta T°  phi P°  (A up)
//   visible SCORE_NAME U = x (p% of the total)          (only with a score)
// with a colour bar labelled SCORE_NAME under it. U is picture_visible_score's; `shown` (may
// be null) receives it (zeros without a score).
Image titled_view(const Mesh& mesh, const std::vector<double>* score, const ViewAngles& view,
                  const RenderStyle& style, const std::string& name, const std::string& score_name,
                  VisibleScore* shown = nullptr);

}  // namespace meshsal
