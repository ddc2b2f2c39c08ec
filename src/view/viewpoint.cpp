#include "view/viewpoint.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <string>

#include "meshsal/meshsal.h"
#include "core/cancel.h"

namespace meshsal {

static const double kPi = 3.14159265358979323846;

LatitudeBand latitude_band(const ElevationRange& r) {
  if (!std::isfinite(r.min) || !std::isfinite(r.max) || r.min < -90 || r.max > 90 || r.min > r.max) {
    char buf[160];
    std::snprintf(buf, sizeof buf, "elevation range must have -90 <= min <= max <= 90 degrees, got min %g, max %g",
                  r.min, r.max);
    throw Error(buf);
  }
  LatitudeBand b;
  if (r.min <= -90 && r.max >= 90) return b;  // the whole sphere
  b.limited = true;
  b.lo = r.min * (kPi / 180.0);
  b.hi = r.max * (kPi / 180.0);
  return b;
}

ElevationRange parse_elevation_range(const std::string& text) {
  const std::string what = "elevation range must be MIN,MAX in degrees (e.g. 0,60)";
  const size_t comma = text.find(',');
  if (comma == std::string::npos || text.find(',', comma + 1) != std::string::npos)
    throw Error(what + ", got '" + text + "'");
  double v[2];
  const std::string part[2] = {text.substr(0, comma), text.substr(comma + 1)};
  for (int i = 0; i < 2; ++i) {
    char* end = nullptr;
    errno = 0;
    v[i] = std::strtod(part[i].c_str(), &end);
    if (part[i].empty() || !end || *end != '\0' || errno == ERANGE || !std::isfinite(v[i]))
      throw Error(what + ", got '" + text + "'");
  }
  ElevationRange r;
  r.min = v[0];
  r.max = v[1];
  latitude_band(r);  // the range check
  return r;
}

std::vector<ViewAngles> fibonacci_directions(int n, const LatitudeBand& band) {
  if (n < 1) throw Error("the number of views must be at least 1, got " + std::to_string(n));
  std::vector<ViewAngles> v(static_cast<size_t>(n));
  const double golden = kPi * (3.0 - std::sqrt(5.0));
  const double sin_lo = std::sin(band.lo), sin_hi = std::sin(band.hi);
  for (int i = 0; i < n; ++i) {
    double y = band.limited ? sin_hi - (sin_hi - sin_lo) * (2.0 * i + 1.0) / (2.0 * n) : 1.0 - (2.0 * i + 1.0) / n;
    double t = std::remainder(golden * i, 2 * kPi);  // in [-pi, pi]
    v[size_t(i)].phi = band.clamp(std::asin(std::clamp(y, -1.0, 1.0)));
    v[size_t(i)].theta = t;
  }
  return v;
}

ViewMap exhaustive_map(const ViewScorer& scorer, int n, int batch, const ProgressFn& progress,
                       const LatitudeBand& band) {
  ViewMap m;
  m.views = fibonacci_directions(n, band);
  m.U.reserve(m.views.size());
  batch = std::max(batch, 1);
  for (size_t b = 0; b < m.views.size(); b += size_t(batch)) {
    size_t e = std::min(m.views.size(), b + size_t(batch));
    std::vector<ViewAngles> part(m.views.begin() + long(b), m.views.begin() + long(e));
    std::vector<double> u = scorer(part);
    if (u.size() != part.size()) throw Error("internal: view scorer returned a wrong count");
    m.U.insert(m.U.end(), u.begin(), u.end());
    if (progress) progress("view map", double(e) / double(m.views.size()));
  }
  m.best = size_t(std::max_element(m.U.begin(), m.U.end()) - m.U.begin());
  return m;
}

ViewAngles rotate_towards(const ViewAngles& a, const double t[3], double angle) {
  double d[3];
  view_direction(a, d);
  double c = std::cos(angle), s = std::sin(angle), r[3];
  for (int k = 0; k < 3; ++k) r[k] = c * d[k] + s * t[k];
  return direction_angles(r);
}

double restart_progress(int iterations, double step, const OptimiserOptions& o) {
  const double by_iterations = double(iterations) / double(std::max(1, o.max_iterations));
  const double way_down = std::log(o.initial_step / o.min_step);
  const double by_step = way_down > 0 ? std::log(o.initial_step / step) / way_down : 0.0;
  return std::clamp(std::max(by_iterations, by_step), 0.0, 1.0);
}

namespace {

struct Restart {
  ViewAngles at;
  double U = 0;
  double step = 0;
  int iterations = 0;
  bool active = true;
  double progress = 0;  // the largest restart_progress seen, 1 once it ends
};

// The multi-start gradient ascent of optimise_viewpoint: each round probes every active
// restart four ways (the views of all of them scored as one batch), then steps each along
// its gradient (a second batch), growing the step on success and halving it otherwise.
class ViewSearch {
 public:
  ViewSearch(const ViewScorer& scorer, const OptimiserOptions& o, const LatitudeBand& band)
      : scorer_(scorer), o_(o), band_(band), rs_(size_t(o.restarts)) {}

  OptimiserResult run() {
    const std::vector<ViewAngles> starts = random_starts();
    report(false);
    std::vector<double> u0 = evaluate(starts);
    for (size_t i = 0; i < rs_.size(); ++i) rs_[i].U = u0[i];
    for (;;) {
      std::vector<size_t> active;
      const std::vector<ViewAngles> probes = probe_views(&active);
      if (active.empty()) break;
      step_along_gradients(active, evaluate(probes));
      for (size_t i : active) {
        Restart& r = rs_[i];
        if (++r.iterations >= o_.max_iterations || r.step < o_.min_step) r.active = false;
      }
    }
    report(true);
    pick_best();
    return res_;
  }

 private:
  // A direction moved by the search, its latitude kept in the band.
  ViewAngles in_band(ViewAngles a) const {
    a.phi = band_.clamp(a.phi);
    return a;
  }

  // Each restart's start, uniform on the sphere: y = sin(phi) uniform in [-1, 1], theta
  // uniform (on the band: y uniform in [sin lo, sin hi]).
  std::vector<ViewAngles> random_starts() {
    std::mt19937_64 rng(o_.seed);
    auto uniform = [&rng]() { return double(rng() >> 11) * (1.0 / 9007199254740992.0); };
    const double sin_lo = std::sin(band_.lo), sin_hi = std::sin(band_.hi);
    std::vector<ViewAngles> batch;
    for (Restart& r : rs_) {
      if (band_.limited)
        r.at.phi = band_.clamp(std::asin(std::clamp(sin_lo + (sin_hi - sin_lo) * uniform(), -1.0, 1.0)));
      else
        r.at.phi = std::asin(2.0 * uniform() - 1.0);
      r.at.theta = (2.0 * uniform() - 1.0) * kPi;
      r.step = o_.initial_step;
      res_.starts.push_back(r.at);
      batch.push_back(r.at);
    }
    return batch;
  }

  // The mean of the restarts' progress, reported after each batch: the restarts end at
  // different rounds, so this rises round by round instead of jumping at the last one.
  void report(bool done) {
    if (!o_.progress) return;
    double sum = 0;
    for (Restart& r : rs_) {
      r.progress = r.active ? std::max(r.progress, restart_progress(r.iterations, r.step, o_)) : 1.0;
      sum += r.progress;
    }
    reported_ = done ? 1.0 : std::max(reported_, std::min(0.99, sum / double(rs_.size())));
    o_.progress("best view", reported_);
  }

  std::vector<double> evaluate(const std::vector<ViewAngles>& views) {
    throw_if_cancelled();
    std::vector<double> u = scorer_(views);
    if (u.size() != views.size()) throw Error("internal: view scorer returned a wrong count");
    res_.views_evaluated += views.size();
    report(false);
    return u;
  }

  // Round 1: four probes of every active restart (right, left, up, down), whose indices go
  // to `active`.
  std::vector<ViewAngles> probe_views(std::vector<size_t>* active) const {
    std::vector<ViewAngles> batch;
    for (size_t i = 0; i < rs_.size(); ++i) {
      const Restart& r = rs_[i];
      if (!r.active) continue;
      active->push_back(i);
      double right[3], up[3], d[3], h = std::min(o_.probe, r.step), neg[3];
      view_basis(r.at, right, up, d);
      for (const double* t : {right, up}) {
        batch.push_back(in_band(rotate_towards(r.at, t, h)));
        for (int k = 0; k < 3; ++k) neg[k] = -t[k];
        batch.push_back(in_band(rotate_towards(r.at, neg, h)));
      }
    }
    return batch;
  }

  // Round 2: one step along each gradient the probes `pu` give (k-th active restart:
  // pu[4k .. 4k + 3]), kept where it scores higher.
  void step_along_gradients(const std::vector<size_t>& active, const std::vector<double>& pu) {
    std::vector<ViewAngles> batch;
    std::vector<size_t> moving;
    for (size_t k = 0; k < active.size(); ++k) {
      Restart& r = rs_[active[k]];
      double right[3], up[3], d[3];
      view_basis(r.at, right, up, d);
      double gr = pu[4 * k] - pu[4 * k + 1], gu = pu[4 * k + 2] - pu[4 * k + 3];
      double norm = std::sqrt(gr * gr + gu * gu);
      if (!(norm > 0)) {
        flat_step(r, pu, k, right, up);
        continue;
      }
      double t[3];
      for (int q = 0; q < 3; ++q) t[q] = (gr * right[q] + gu * up[q]) / norm;
      batch.push_back(in_band(rotate_towards(r.at, t, r.step)));
      moving.push_back(active[k]);
    }
    if (moving.empty()) return;
    std::vector<double> mu = evaluate(batch);
    for (size_t k = 0; k < moving.size(); ++k) {
      Restart& r = rs_[moving[k]];
      if (mu[k] > r.U) {
        r.U = mu[k];
        r.at = batch[k];
        r.step = std::min(r.step * 1.5, 4.0 * o_.initial_step);
      } else {
        r.step *= 0.5;
      }
    }
  }

  // Flat here at this probe size: if a probe itself is better, move there; else shrink.
  void flat_step(Restart& r, const std::vector<double>& pu, size_t k, const double right[3], const double up[3]) const {
    size_t bi = size_t(std::max_element(pu.begin() + long(4 * k), pu.begin() + long(4 * k + 4)) - pu.begin());
    if (pu[bi] > r.U) {
      r.U = pu[bi];
      double t[3];
      int which = int(bi - 4 * k);
      const double* axis = which < 2 ? right : up;
      for (int q = 0; q < 3; ++q) t[q] = which % 2 == 0 ? axis[q] : -axis[q];
      r.at = in_band(rotate_towards(r.at, t, std::min(o_.probe, r.step)));
    } else {
      r.step *= 0.5;
    }
  }

  // The restarts' ends and the best of them (the first of equals).
  void pick_best() {
    size_t best = 0;
    for (size_t i = 0; i < rs_.size(); ++i) {
      res_.finals.push_back(rs_[i].at);
      res_.final_U.push_back(rs_[i].U);
      if (rs_[i].U > rs_[best].U) best = i;
    }
    res_.best = rs_[best].at;
    res_.U = rs_[best].U;
    if (!(res_.U > 0)) {
      // Every view tried sees nothing (a score of 0 everywhere: one triangle, a small fan):
      // any start would "win", so say so and give the front view instead of a random one.
      res_.best = ViewAngles{};
      res_.best.phi = band_.clamp(0.0);  // the front view, or the band's latitude nearest it
      res_.U = evaluate({res_.best})[0];
      if (res_.best.phi == 0)
        res_.note = "no view sees any score (U = 0 from every direction tried; is the score 0 everywhere?): "
                    "the front view (theta 0, phi 0) is returned";
      else
        res_.note = "no view sees any score (U = 0 from every direction tried; is the score 0 everywhere?): "
                    "theta 0 at the elevation range's latitude nearest 0 is returned";
    }
  }

  const ViewScorer& scorer_;
  const OptimiserOptions& o_;
  const LatitudeBand& band_;
  OptimiserResult res_;
  std::vector<Restart> rs_;
  double reported_ = 0;
};

}  // namespace

OptimiserResult optimise_viewpoint(const ViewScorer& scorer, const OptimiserOptions& o, const LatitudeBand& band) {
  const CancelScope cancel(o.cancel);
  if (o.restarts < 1) throw Error("restarts must be at least 1");
  if (!(o.probe > 0) || !(o.initial_step > 0) || !(o.min_step > 0))
    throw Error("optimiser probe and step sizes must be positive");
  return ViewSearch(scorer, o, band).run();
}

}  // namespace meshsal
