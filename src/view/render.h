// meshsal: pictures. A small CPU z-buffer renderer (the orthographic camera of camera.h),
// Lambert shading with a light near the viewer, per-vertex colours; the equirectangular map
// of U over view directions (the paper's figure 10); side-by-side comparisons.
#pragma once
#include <cstdint>
#include <vector>

#include "view/camera.h"
#include "io/colormap.h"
#include "meshsal/meshsal.h"
#include "io/png_image.h"
#include "view/viewpoint.h"

namespace meshsal {

// Checks size (kMinImageSize..kMaxImageSize), margin (>= 1) and supersample (1..4); throws Error otherwise.
void check_render_style(const RenderStyle& style);

// The square of the view plane a picture shows: centre (cx, cy) along the view's right and up
// axes (mesh units, from frame.centre) and half side `half` (before style.margin).
struct PictureFit {
  double cx = 0, cy = 0, half = 1;
};

// The mesh points' projected extent in `view`, centred: the mesh fills the picture.
PictureFit fit_picture(const Mesh& mesh, const ViewFrame& frame, const ViewAngles& view);

// Renders the mesh seen from `view` (frame: centre, depth range and up axis; fit: the square
// shown, nullptr = fit_picture of this mesh) at style.supersample times the size, averaged
// down. vertex_rgb: 3 bytes per vertex (nullptr = style.base). Colours are interpolated
// across triangles, then shaded. style.up is not read: it is in frame (frame_mesh).
Image render_mesh(const Mesh& mesh, const std::vector<uint8_t>* vertex_rgb,
                  const ViewFrame& frame, const ViewAngles& view, const RenderStyle& style,
                  const PictureFit* fit = nullptr);

// Colours of a per-vertex score for pictures, on the one colour scale (colormap.h) over the
// mesh points; `limits` (optional) receives the resolved ends for the colour bar.
std::vector<uint8_t> score_colours(const Mesh& mesh, const std::vector<double>& score,
                                   const ColorRange& range = {}, ColorLimits* limits = nullptr);

// Equirectangular plot (width x width/2) of U over directions: theta -180..180 degrees left to
// right, phi 90..-90 top to bottom, U smoothed over the nearby map directions and coloured on the
// colour scale (colormap.h) from its minimum (blue) to its maximum (red); grid lines every 30 degrees. A white ring with a
// black rim marks `ring` (e.g. the exhaustive maximum), a black cross with a white rim `cross`
// (e.g. the optimiser's result): both show on any colour.
Image render_view_map(const ViewMap& map, int width, const ViewAngles* ring = nullptr,
                      const ViewAngles* cross = nullptr);

// Pixel of a direction in render_view_map's image.
void view_map_pixel(const ViewAngles& a, int width, int* x, int* y);

// The meshes side by side (left to right, same camera and framing `frame`), each with its
// colours (nullptr = style.base), separated by a 4-pixel gap.
Image render_side_by_side(const std::vector<const Mesh*>& meshes,
                          const std::vector<const std::vector<uint8_t>*>& colours,
                          const ViewFrame& frame, const ViewAngles& view, const RenderStyle& style);

}  // namespace meshsal
