// meshsal: exposure, how much of the typical views of an object each point gets: the cue
// of the perceptual model (Model::Perceptual, Exposure and Centre; docs/method.md) that
// says what a viewer can see at all.
//
// Over a fixed set of views (exposure_views: rings around the up axis across the default
// elevation band), each point scores, per view in which it is visible (the z-buffer test of
// visibility.h, same camera and rule as the viewpoint search),
//   |n . d|                         with `facing`: the image area a unit of surface takes
//                                   up (a fixation lands on the image, so a surface seen
//                                   at a slant gathers fewer per unit of its area); the
//                                   magnitude, so that the winding does not matter (the
//                                   z-buffer already hides the far side of a closed
//                                   surface; the inside of an open one is seen);
//   exp(-x^2/(2 vx) - y^2/(2 vy))   with `centre`: the centre bias of the view, x and y the
//                                   point's place in the frame ([-1, 1] across the bounding
//                                   sphere), vx = 0.22 and vy = 0.45 vx, the anisotropic
//                                   Gaussian Clarke & Tatler (2014) propose as the
//                                   baseline of image-independent fixation biases;
// and exposure = the mean of those products over the views (0 where it is never seen).
// The products are floats computed by exposure_weight, the very expression the GPU twin
// (shaders/exposure_test.comp) evaluates; the sum over views runs in view order in double.
#pragma once
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "meshsal/meshsal.h"
#include "view/camera.h"

namespace meshsal {

// The z-buffers' side: a mean over 48 views wants no more (the viewpoint search's 512 decides
// one view's edge).
constexpr int kExposureResolution = 256;

// The views: kExposureLongitudes longitudes (every 22.5 degrees from theta 0) on each of
// kExposureLatitudes latitudes spread evenly over kDefaultElevationMin..Max (10, 20 and 30
// degrees): 48 views.
constexpr int kExposureLongitudes = 16, kExposureLatitudes = 3;
std::vector<ViewAngles> exposure_views();

// The centre bias's variances, in frame units (Clarke & Tatler 2014).
constexpr float kCentreVarianceX = 0.22f, kCentreVarianceY = 0.45f * 0.22f;

// What each visible (point, view) pair scores (both false: 1, plain visibility).
struct ExposureWeighting {
  bool facing = true;
  bool centre = true;
};

// One view as the exposure test needs it: the projection rows and the unit direction d
// towards the viewer (float), both in the mesh's coordinates.
struct ExposureView {
  ViewRows rows;
  float direction[3];
};
ExposureView exposure_view(const ViewFrame& frame, const ViewAngles& view);

// The score of a point at p with unit normal n (floats) in one view, given that it is
// visible there. Plain float arithmetic in a fixed order: the shader writes the same.
inline float exposure_weight(const ExposureView& v, const float p[3], const float n[3], ExposureWeighting w) {
  float s = 1.0f;
  if (w.facing) {
    const float f = n[0] * v.direction[0] + n[1] * v.direction[1] + n[2] * v.direction[2];
    s = std::fabs(f);
  }
  if (w.centre) {
    const float* r0 = v.rows.row[0];
    const float* r1 = v.rows.row[1];
    const float x = r0[0] * p[0] + r0[1] * p[1] + r0[2] * p[2] + r0[3];
    const float y = r1[0] * p[0] + r1[1] * p[1] + r1[2] * p[2] + r1[3];
    s *= std::exp(-(x * x) / (2.0f * kCentreVarianceX) - (y * y) / (2.0f * kCentreVarianceY));
  }
  return s;
}

// Unit area-weighted vertex normals as floats (3 per vertex; 0 where they vanish): the
// normals both twins take.
std::vector<float> exposure_normals(const Mesh& mesh, unsigned threads = 0);

// The most bytes of projections and z-buffers exposure_cpu holds at once (views rasterised
// side by side: 12 bytes a vertex and the z-buffer each).
constexpr size_t kExposureScratch = size_t(1) << 30;

// Exposure of every vertex (0 for vertices that are not mesh points) over `views`, on the
// CPU: the z-buffers of a batch of views are rasterised in parallel (as many as the threads
// within kExposureScratch), then each vertex adds its scores over the batch's views in order. options: the z-buffer's side, depth
// tolerance and threads. `normals` as exposure_normals. The same values on any thread count.
std::vector<double> exposure_cpu(const Mesh& mesh, const std::vector<float>& normals, const ViewFrame& frame,
                                 const std::vector<ViewAngles>& views, ExposureWeighting weighting,
                                 const VisibilityOptions& options);

// The same by the plain route, one view at a time with visible_vertices_cpu and the
// weights in double: the oracle exposure_cpu is tested against.
std::vector<double> exposure_plain_cpu(const Mesh& mesh, const std::vector<float>& normals, const ViewFrame& frame,
                                       const std::vector<ViewAngles>& views, ExposureWeighting weighting,
                                       const VisibilityOptions& options);

}  // namespace meshsal
