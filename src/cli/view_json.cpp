#include "view_json.h"

namespace meshsal::cli {

JsonObject& add_view(JsonObject& j, const meshsal::ViewFrame& frame, const meshsal::ViewAngles& view) {
  const double deg = 180.0 / 3.14159265358979323846;
  double d[3];
  meshsal::view_direction(frame, view, d);
  return j.number("theta", view.theta).number("phi", view.phi).number("theta_deg", view.theta * deg)
      .number("phi_deg", view.phi * deg).numbers("direction", {d[0], d[1], d[2]});
}

}  // namespace meshsal::cli
