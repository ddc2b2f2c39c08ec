// meshsal bench --simplify: simplification quality and speed on real meshes (plain quadrics,
// the paper's weighting, the balanced preset, meshoptimizer) and the trade-off between the
// salient-region error and the RMS error over a sweep of the weighting's parameters.
#pragma once
#include <string>
#include <vector>

namespace meshsal::cli {

// The weighting parameters the benchmark sweeps (--sweep): short (the benchmark's plot), wide
// (the search behind the balanced preset) or none.
enum class SweepSet { Short, Wide, None };

// "short", "wide" or "none"; throws UsageError otherwise.
SweepSet parse_sweep(const std::string& name);

struct SimplifyBenchArgs {
  std::vector<std::string> meshes;  // empty: the four default models from data_dir
  std::string data_dir;
  bool json = false;
  int repeat = 3;
  unsigned threads = 0;
  std::string plot;                 // PNG of the trade-off; "" = none
  SweepSet sweep = SweepSet::Short;
};

// Runs the benchmark; prints a table (or one JSON object with --json). Returns the exit code.
int run_simplify_benchmark(const SimplifyBenchArgs& args);

}  // namespace meshsal::cli
