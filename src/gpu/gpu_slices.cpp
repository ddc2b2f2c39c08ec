// meshsal: slices of the GPU sweep (see gpu_slices.h).
#include "gpu/gpu_slices.h"

#include <algorithm>
#include <cmath>

namespace meshsal {

SweepWork sweep_work(const GridPlan& g, const std::vector<uint32_t>& starts, double radius) {
  const int r = int(std::ceil(radius / g.h));
  SweepWork w;
  double acc = 0;
  const int nx = g.nx, ny = g.ny, nz = g.nz;
  for (int z = 0; z < nz; ++z)
    for (int y = 0; y < ny; ++y)
      for (int x = 0; x < nx; ++x) {
        uint32_t c = uint32_t(x) + g.nx * (uint32_t(y) + g.ny * uint32_t(z));
        uint32_t pts = starts[c + 1] - starts[c];
        if (!pts) continue;
        double cand = 0;
        int x0 = std::max(x - r, 0), x1 = std::min(x + r, nx - 1);
        for (int zz = std::max(z - r, 0); zz <= std::min(z + r, nz - 1); ++zz)
          for (int yy = std::max(y - r, 0); yy <= std::min(y + r, ny - 1); ++yy) {
            uint32_t row = g.nx * (uint32_t(yy) + g.ny * uint32_t(zz));
            cand += starts[row + x1 + 1] - starts[row + x0];
          }
        w.first.push_back(starts[c]);
        w.before.push_back(acc);
        acc += cand * pts;
      }
  w.first.push_back(starts.back());
  w.before.push_back(acc);
  return w;
}

size_t next_cut(const SweepWork& w, size_t from, double budget) {
  const double limit = w.before[from] + budget;
  // The last cut whose work fits, but at least the next one.
  size_t cut = size_t(std::upper_bound(w.before.begin() + from + 1, w.before.end(), limit) -
                      w.before.begin());
  return std::max(from + 1, cut - 1);
}

double next_budget(double budget, double work, double seconds, double target_s) {
  if (!(seconds > 0) || !(work > 0)) return budget * 4;
  return std::min(budget * 4, work / seconds * target_s);
}

double first_slice_budget(bool cpu_device, double total_work) {
  // lavapipe sweeps ~1e8 pairs/s per core: 2e7 is ~0.1 s on two cores. A GPU's first
  // slice of 2e8 pairs is ~1 ms on an H100 and ~0.1 s even at a slow consumer card's
  // fp64 rate.
  return std::min(cpu_device ? 2e7 : 2e8, total_work / 16);
}

}  // namespace meshsal
