// meshsal CLI: a view direction in the JSON of `viewpoint` and `render`.
#pragma once
#include "json_object.h"
#include "meshsal/meshsal.h"
#include "view/camera.h"

namespace meshsal::cli {

// Adds "theta", "phi" (radians), "theta_deg", "phi_deg" (the angles in `frame`'s up axis, as
// --theta/--phi take them) and "direction" (the unit vector towards the viewer, in the mesh's
// coordinates) to `j`.
JsonObject& add_view(JsonObject& j, const meshsal::ViewFrame& frame, const meshsal::ViewAngles& view);

}  // namespace meshsal::cli
