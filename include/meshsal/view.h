// meshsal public interface: viewpoints (the paper's section 5), cameras, pictures and
// viewer pages.
// Part of meshsal.h (which includes every part); the conventions at the top of
// meshsal.h hold for every function here.
#pragma once
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "meshsal/device.h"
#include "meshsal/mesh.h"

namespace meshsal {

// ------------------------------------------------------------------------------------------
// Viewpoints (the paper's section 5) and pictures

// Which axis of the mesh is up in pictures and in view angles. The angles of ViewAngles are
// taken in a frame where this axis plays the part of +y: for Z, theta 0 looks from -y (the
// front of a z-up scan), theta 90 degrees from +x, phi 90 degrees from +z (above).
enum class UpAxis { Y, MinusY, Z, MinusZ, X, MinusX };

// Direction d(theta, phi) = (cos phi sin theta, sin phi, cos phi cos theta), y up:
// (0, 0) looks from +z, theta = pi/2 from +x, phi = pi/2 from above. Radians.
struct ViewAngles {
  double theta = 0;  // longitude, in (-pi, pi]
  double phi = 0;    // latitude, in [-pi/2, pi/2]
};

// The z-buffer that decides which mesh points a view sees (ViewpointOptions::visibility).
struct VisibilityOptions {
  int resolution = 256;       // z-buffer side in pixels, 16..8192 (the search: kDefaultViewResolution)
  double depth_tol_px = 2.0;  // depth tolerance in pixel widths, >= 0
  unsigned threads = 0;       // CPU threads (views in parallel), 0 = all cores
};

// The gradient ascent of the viewpoint search (ViewpointOptions::optimiser).
struct OptimiserOptions {
  int restarts = 8;              // random starts of the gradient ascent, >= 1
  uint64_t seed = 1;             // runs with the same seed repeat
  double probe = 0.05;           // probe angle (radians) for the central differences
  double initial_step = 0.25;    // first step length along the gradient (radians)
  double min_step = 0.01;        // a restart stops when its step shrinks below this
  int max_iterations = 60;       // per restart
  // Called after each batch of views scored, from the calling thread, with a stage name and
  // the fraction done of that stage (0..1, never falling, 1 when it ends): "best view" for
  // the gradient ascent (an estimate: each restart's share of its iterations or of its
  // step's way down to min_step, whichever is further), then, in best_viewpoint with
  // views > 0, "view map" (views scored / views). May be empty.
  std::function<void(const char* stage, double fraction)> progress;
  const std::atomic<bool>* cancel = nullptr;  // as SaliencyOptions::cancel (best_viewpoint too)
};

struct OptimiserResult {
  ViewAngles best;
  double U = 0;                      // visible score of `best`
  std::vector<ViewAngles> starts;    // the random start of each restart
  std::vector<ViewAngles> finals;    // where each restart ended
  std::vector<double> final_U;
  uint64_t views_evaluated = 0;
  // Set when no direction tried saw anything (U = 0 everywhere): `best` is then the front
  // view (0, 0), not an arbitrary start, and this says why.
  std::string note;
};

struct ViewMap {
  std::vector<ViewAngles> views;
  std::vector<double> U;
  size_t best = 0;  // index of the largest U
};

// The z-buffer side of the viewpoint search: ViewpointOptions::visibility.resolution's
// default, and so that of every front end (`meshsal viewpoint`, `render --best`, `batch
// --view`, Python).
constexpr int kDefaultViewResolution = 512;

// Limits of the view and picture settings: every check and its message, in the library and
// the front ends, is built from these.
// The side in pixels of every square picture and z-buffer: RenderStyle::size,
// VisibilityOptions::resolution and ViewpointOptions::resolution (--size, --resolution).
constexpr int kMinImageSize = 16, kMaxImageSize = 8192;
constexpr int kMinMapWidth = 32;  // the view map picture (--map): kMinMapWidth..kMaxImageSize wide
// What the front ends accept for the viewpoint search (--restarts, --views, --depth-tol).
constexpr int kMaxViewRestarts = 1000, kMaxViewMapViews = 1000000, kMaxDepthTolPx = 1000;

// The latitudes (degrees, in the frame of the up axis) the best view is searched within
// unless told otherwise, by every front end (viewpoint, render --best, view, batch, Python):
// a photographer's view of an object, a little above the horizon. Unconstrained, visible
// saliency pulls the view below scans (into their holes, up a bust's nostrils or neck) or
// straight down onto them; this band was chosen by looking at the shared scans' views
// (docs/method.md, "Elevation range"). {-90, 90} is the paper's unconstrained search.
constexpr double kDefaultElevationMin = 10, kDefaultElevationMax = 30;

// A band of latitudes, in degrees, in the frame of the up axis: -90 <= min <= max <= 90.
// The default is kDefaultElevationMin..kDefaultElevationMax.
struct ElevationRange {
  double min = kDefaultElevationMin;
  double max = kDefaultElevationMax;
};

// Everything that picks a view. Every front end fills this and calls best_viewpoint, so the
// same settings give the same view to the last bit (docs/method.md, "One view pipeline").
struct ViewpointOptions {
  UpAxis up = UpAxis::Y;                    // the frame of the angles: searched, limited, returned
  // The latitudes (phi, in the frame of `up`) the search may look from: the random starts
  // are uniform on that band of the sphere, every probe and step stays in it, and the
  // exhaustive map's directions are spread over it. Error when out of range (above).
  ElevationRange elevation;
  // The gradient ascent: restarts, seed, steps; its progress ("best view", then "view map"
  // with views > 0) and cancel hold for the whole search.
  OptimiserOptions optimiser;
  // The z-buffer: resolution (kDefaultViewResolution here, not VisibilityOptions' own
  // 256), depth tolerance and CPU threads.
  VisibilityOptions visibility = [] {
    VisibilityOptions v;
    v.resolution = kDefaultViewResolution;
    return v;
  }();
  int views = 0;                            // also score this many directions exhaustively, >= 0
  Backend backend = Backend::Cpu;           // as SaliencyOptions::backend (visibility)
  int device = -1;                          // Vulkan device index, -1 = choose
  Device* session = nullptr;                // as SaliencyOptions::session (visibility)
  // Called with a one-line notice (e.g. Backend::Auto found no GPU); also kept in
  // Viewpoint::notices. May be empty.
  std::function<void(const std::string&)> notice;
};

// The camera of a view: orthographic, looking from `eye` towards `target` (mesh
// coordinates), `up` the picture's up direction (unit), framing a square of half side
// `half_extent` model units around `target` (before RenderStyle::margin). view_camera()
// makes it; render_camera_view(mesh, score, camera, style) renders exactly that picture.
struct ViewCamera {
  ViewAngles view;              // the direction, in the frame of up_axis
  UpAxis up_axis = UpAxis::Y;
  double eye[3] = {0, 0, 0};     // target + radius * direction (radius: the bounding sphere's)
  double target[3] = {0, 0, 0};  // the centre of the picture
  double up[3] = {0, 1, 0};      // unit, the picture's up
  double direction[3] = {0, 0, 1};  // unit, from the mesh towards the viewer
  double half_extent = 1;       // half the side of the square shown, model units
};

// The camera render_view uses for `view` (angles in the frame of `up`) on this mesh: centred
// on the mesh points' projected extent, which it frames. Throws Error on an empty mesh.
ViewCamera view_camera(const Mesh& mesh, const ViewAngles& view, UpAxis up = UpAxis::Y);

// The result of the viewpoint search. Angles are in the frame of ViewpointOptions::up.
struct Viewpoint {
  ViewAngles view;                   // the best direction found (optimised.best)
  double U = 0;                      // its visible score
  double total = 0;                  // the score summed over all mesh points (as U sums it)
  double visible_fraction = 0;       // U / total (0 when total is 0)
  UpAxis up = UpAxis::Y;             // the frame of every angle here
  ViewCamera camera;                 // view_camera(mesh, view, up)
  OptimiserResult optimised;         // gradient ascent from seeded random starts
  ViewMap map;                       // the exhaustive map (empty without views)
  std::string note;                  // optimised.note: why the front view, when nothing was seen
  std::vector<std::string> notices;  // what options.notice heard
  std::string backend_name;          // where the views were scored
};

// The view of largest visible score U = sum of score over the visible mesh points (`score`:
// one value per vertex, e.g. SaliencyResult::saliency; finite and >= 0 on the mesh points,
// else Error), searched in the frame of options.up within options.elevation. The search runs
// on the mesh's coordinates turned into that frame (an exact permutation of the axes), so a
// mesh turned so that z is up, searched with up Z, gives the angles of the original with up
// Y. Throws Error for an option out of range.
Viewpoint best_viewpoint(const Mesh& mesh, const std::vector<double>& score,
                         const ViewpointOptions& options = {});

// The one colour scale of every picture and of the saliency PLY's vertex colours: a value v
// is placed at t = sqrt((v - lo) / (hi - lo)), clamped to [0, 1], and t runs through Turbo
// from blue (t = 0, RGB 73 88 221) through cyan, green and yellow to dark red (t = 1,
// 155 15 0); colour bars place their value ticks the same way. lo and hi are values, or
// percentiles (0..100) of the values over the mesh points. The default, 0th to 100th
// percentile (minimum to maximum), is unclipped, so the hottest colour means the highest
// values only (a percentile clip painted the demo's ~900 bumps as red as its unique
// feature); the square root spreads the moderate values (a face's eyes, nose and mouth)
// over more colours than a linear scale would.
struct ColorRange {
  double lo = 0, hi = 100;
  bool lo_percentile = true, hi_percentile = true;
};

// What a viewer page shows besides the model (write_view_page).
struct ViewPageOptions {
  std::string title;                                        // the page's heading (the file name)
  std::vector<std::pair<std::string, std::string>> stats;  // rows of the statistics table
  std::string note;                                         // a line the page shows ("" = none)
  // A mesh with more faces is shown as a copy simplified to this many (plain quadrics,
  // the saliency carried along; or as close as the simplifier gets, ViewPageReport), and
  // the page says so; 0 = never.
  size_t max_faces = 2000000;
  // The ends of the colour scale the page opens with (ColorRange; minimum to maximum); the
  // page's range control and its "r" key come back to them.
  ColorRange range;
  // The camera's view as the search scored it (Viewpoint::U and visible_fraction, what
  // `meshsal viewpoint` reports), shown with its angles; < 0: not shown.
  double visible_score = -1, visible_fraction = -1;
  // "" (the default): the viewer inline, the page alone is all it needs. Else the URL,
  // relative to the page, of the viewer file write_viewer_script writes (a gallery's pages
  // share one: `batch --html` writes meshsal-viewer.js beside index.html), which the page
  // loads with <script src>; the page then holds the model and its numbers only.
  std::string viewer_script;
};

// True when this build has the web viewer (three.js bundled at build time from web/;
// tools/setup.sh installs what it needs): write_view_page works.
bool built_with_viewer();

// What write_view_page drew.
struct ViewPageReport {
  size_t shown_faces = 0;         // the faces of the mesh the page shows
  bool simplified = false;        // a copy simplified towards ViewPageOptions::max_faces
  // shown_faces <= max_faces; false when the simplifier could go no further (a closed
  // surface keeps at least 4 faces; refused collapses), which the page's note then says.
  bool within_max_faces = true;
};

// Writes one self-contained HTML page (no network needed to open it): the mesh coloured by
// `saliency` (one value per vertex) on the pictures' colour scale with its colour bar and
// scale, orbit controls from `camera` (best_viewpoint's Viewpoint::camera for this mesh)
// with a button back to it, saliency or plain shading with or without lit edges, a
// colour-range control, S and its percentile under the cursor, the view's angles and
// options.stats, with keyboard shortcuts (web/page.html lists them). The mesh is embedded as
// a small GLB (local coordinates, positions quantised to 16 bits of its bounding box, S as
// float; meshopt-compressed when built with meshoptimizer), three.js (MIT licence, kept in
// the page) inline unless options.viewer_script names a shared file. The title, statistics and note are shown as their bytes are (no markup,
// bytes that are not UTF-8 and bidirectional controls escaped). Atomic as write_ply. Error
// when built without the viewer.
ViewPageReport write_view_page(const std::string& path, const Mesh& mesh, const std::vector<double>& saliency,
                               const ViewCamera& camera, const ViewPageOptions& options = {});

// Writes the viewer's script (three.js and web/viewer.js, bundled at build time), for pages
// written with ViewPageOptions::viewer_script naming it. Atomic as write_ply; Error when
// built without the viewer.
void write_viewer_script(const std::string& path);

// An 8-bit RGB image, rows top to bottom.
struct Image {
  int width = 0, height = 0;
  std::vector<uint8_t> rgb;  // 3 bytes per pixel

  Image() = default;
  Image(int w, int h, uint8_t r = 255, uint8_t g = 255, uint8_t b = 255);
  uint8_t* at(int x, int y) { return &rgb[(size_t(y) * size_t(width) + size_t(x)) * 3]; }
  const uint8_t* at(int x, int y) const { return &rgb[(size_t(y) * size_t(width) + size_t(x)) * 3]; }
};

struct RenderStyle {
  int size = 512;            // square image side in pixels, 16..8192
  double margin = 1.05;      // the image frames the mesh's projected extent times this, >= 1
  bool smooth = true;        // interpolated vertex normals; false: flat faces
  bool edges = false;        // darken the edges of triangles at least 4 px tall
  int supersample = 2;       // anti-aliasing: rendered at this many times the size, averaged; 1..4
  UpAxis up = UpAxis::Y;     // the mesh axis that points up in the picture (see UpAxis)
  ColorRange range;          // the colour scale's ends (see ColorRange)
  uint8_t background[3] = {255, 255, 255};
  uint8_t base[3] = {190, 190, 190};  // surface colour when there are no vertex colours
};

// The mesh seen from `view` (orthographic, square image framed by the mesh's projected
// extent in that view, centred), Lambert-shaded, coloured by `score` (one value per vertex,
// empty: plain grey) on the colour scale of style.range. Only the mesh: the CLI's
// pictures add a title line and a colour bar. Throws Error for a style out of range.
Image render_view(const Mesh& mesh, const std::vector<double>& score, const ViewAngles& view,
                  const RenderStyle& style = {});

// The same from a camera made by view_camera (or best_viewpoint) for this mesh: the picture
// of camera.view with camera.up_axis as the up axis (style.up is not read), pixel for pixel
// that of render_view(mesh, score, camera.view, style with up = camera.up_axis). (Its own
// name: an overload of render_view would make render_view(mesh, s, {}, style) ambiguous.)
Image render_camera_view(const Mesh& mesh, const std::vector<double>& score, const ViewCamera& camera,
                         const RenderStyle& style = {});

// Writes a PNG (atomically, as write_ply). Throws Error naming the file.
void write_png(const std::string& path, const Image& image);

// What the views and pictures of a run are coloured by and search for.
enum class Score {
  Saliency,  // S (computed, or read back)
  Curvature  // |H|, the mean curvature's magnitude: the paper's baseline
};

}  // namespace meshsal
