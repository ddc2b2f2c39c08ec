// meshsal: best viewpoint by visible score (SPEC 3): gradient ascent from seeded random
// starts, and the exhaustive map over a Fibonacci sphere of directions.
#pragma once
#include <cstdint>
#include <functional>
#include <vector>

#include "view/camera.h"

namespace meshsal {

// U for a batch of views (the CPU twin or the GPU path); batches let the GPU path evaluate
// all probes of all restarts in one submission.
using ViewScorer = std::function<std::vector<double>(const std::vector<ViewAngles>&)>;

// The latitudes (radians) a search keeps to: [lo, hi] when `limited`, else the whole sphere,
// and then every function below runs exactly as it did before bands existed.
struct LatitudeBand {
  bool limited = false;
  double lo = -1.5707963267948966, hi = 1.5707963267948966;
  double clamp(double phi) const { return limited ? (phi < lo ? lo : (phi > hi ? hi : phi)) : phi; }
};

// The band of an ElevationRange (degrees); limited unless it is the whole sphere. Throws
// Error unless -90 <= min <= max <= 90 (both finite).
LatitudeBand latitude_band(const ElevationRange& range);

// n directions spread evenly over the sphere (golden-angle spiral in the y = sin(phi) axis):
// y_i = 1 - (2 i + 1) / n, theta_i = i * pi (3 - sqrt 5). With a limited band, over that band
// only: y_i = sin hi - (sin hi - sin lo) (2 i + 1) / (2 n), the same thetas.
std::vector<ViewAngles> fibonacci_directions(int n, const LatitudeBand& band = {});

// Progress callback: stage name, fraction done of that stage (as SaliencyOptions::progress).
using ProgressFn = std::function<void(const char* stage, double fraction)>;

// U over n Fibonacci directions, evaluated in batches of `batch` views; `progress` (may be
// empty) hears "view map" and the share of views scored after each batch.
ViewMap exhaustive_map(const ViewScorer& scorer, int n, int batch = 256, const ProgressFn& progress = {},
                       const LatitudeBand& band = {});

// Gradient ascent on the sphere of directions. Each iteration of each restart probes the
// four neighbours of the current direction d at angle h along the camera's right and up
// axes (these are the theta and phi directions, right being d_theta / cos phi, so this is
// the gradient in (theta, phi) with the sphere's metric), then moves d by `step` along the
// gradient. A move that raises U is taken and the step grows 1.5x (up to 4x the initial),
// otherwise the step halves; the probe angle follows the step down (h = min(probe, step)).
// All restarts advance in lockstep so each round is one scorer batch. options.progress
// hears "best view" after every batch (optimiser_progress of the restarts). With a limited
// band the random starts are uniform on the band (sin phi uniform in [sin lo, sin hi]) and
// every probe and step has its latitude clamped into it, so no view outside is scored.
OptimiserResult optimise_viewpoint(const ViewScorer& scorer, const OptimiserOptions& options,
                                   const LatitudeBand& band = {});

// How far one restart is, 0..1: the larger of its share of max_iterations and of the way
// its step has shrunk from initial_step towards min_step (in log scale, where it ends).
// Its step may grow again, so callers keep the largest value seen (the estimate never falls).
double restart_progress(int iterations, double step, const OptimiserOptions& options);

// Rotates d by `angle` towards the unit tangent t (both unit, t orthogonal to d).
ViewAngles rotate_towards(const ViewAngles& a, const double t[3], double angle);

}  // namespace meshsal
