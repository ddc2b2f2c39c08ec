// meshsal: how the GPU sweep is split into submissions. A desktop GPU's driver resets the
// device when one submission runs past its watchdog (~2 s), and a long submission stalls
// the display; so the sorted points are swept in slices of whole cells, the first one
// small and timed, the rest sized from the measured rate to about
// Context::submission_target_s each.
#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

#include "gpu/gpu_grid.h"

namespace meshsal {

// Where slices may start (the first sorted point of each non-empty cell, then the point
// count) and the candidate pairs swept before each: before[i] for the points below
// first[i]. A point's candidates are the points of the rows of cells in its cube of
// cells (what the sweep shaders visit).
struct SweepWork {
  std::vector<uint32_t> first;
  std::vector<double> before;
};
SweepWork sweep_work(const GridPlan& g, const std::vector<uint32_t>& starts, double radius);

// The cut after `from` that takes as much work as fits `budget`, at least one cell.
size_t next_cut(const SweepWork& w, size_t from, double budget);

// The budget of the next slice from the last one's `work` and `seconds`: the measured
// rate times target_s, growing by at most 4x a slice (a first slice dominated by fixed
// costs under-measures the rate, so the sizes climb to it rather than jump).
double next_budget(double budget, double work, double seconds, double target_s);

// The first, timed slice: small enough to stay far below any watchdog on a slow device,
// and at most 1/16 of the total work, so that the rate is known early.
double first_slice_budget(bool cpu_device, double total_work);

}  // namespace meshsal
