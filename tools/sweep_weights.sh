#!/bin/sh
# The search behind `--weights balanced` (docs/method.md, "Weightings"): simplifies each
# model to 1% and 5% of its faces with plain quadrics, the paper's recipe, the balanced
# preset, meshoptimizer and 25 settings of the weighting curves (threshold, rank step and
# ramp, continuous, floors; `bench --simplify --sweep wide`), and prints every setting's
# salient-region, RMS and Hausdorff error relative to plain, then the settings ranked by how
# many cases meet the target (salient <= 0.8x, RMS and Hausdorff <= 1.25x plain).
#
#   tools/sweep_weights.sh [MESHES...]      (default: armadillo_43k, dragon_50k, igea_134k,
#                                            lucy_50k from ../shared/data/meshes)
# Env: MESHSAL (default build/meshsal), PLOT (a PNG of the trade-off, default none),
# JSON=1 for the JSON tables instead. About 10 min on 2 busy cores (the run in docs/method.md).
set -eu
cd "$(dirname "$0")/.."
MESHSAL=${MESHSAL:-build/meshsal}
set -- bench --simplify --sweep wide --repeat 1 "$@"
[ -n "${PLOT:-}" ] && set -- "$@" --plot "$PLOT"
[ "${JSON:-0}" = 1 ] && set -- "$@" --json
exec "$MESHSAL" "$@"
