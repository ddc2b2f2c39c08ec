#!/usr/bin/env bash
# Sets up (packages + build) if needed, then runs the whole test suite through ctest, and
# the Vulkan tests (label gpu) three more times: on the discrete-GPU memory path (device-
# local buffers, transfers through the staging area) and at lavapipe's other subgroup sizes
# (LP_NATIVE_VECTOR_WIDTH=128: 4 lanes, 512: 16 lanes; the default, 256, gives 8), and
# the CPU saliency tests once more on the baseline x86-64 loops (MESHSAL_CPU_BASELINE=1;
# the first run takes the AVX2 ones where the CPU has AVX2: README "Portable build").
# Extra arguments go to every ctest run.
set -euo pipefail
cd "$(dirname "$0")/.."
tools/setup.sh
cd build
jobs="$(nproc)"
status=0
run() {
  echo "== $1"
  shift
  env "$@" || status=1
}
run "all tests" ctest --output-on-failure -j"$jobs" "$@"
run "gpu tests, forced staging (MESHSAL_FORCE_STAGING=1)" \
  MESHSAL_FORCE_STAGING=1 ctest --output-on-failure -j"$jobs" -L gpu "$@"
run "gpu tests, subgroups of 4 (LP_NATIVE_VECTOR_WIDTH=128)" \
  LP_NATIVE_VECTOR_WIDTH=128 ctest --output-on-failure -j"$jobs" -L gpu "$@"
run "gpu tests, subgroups of 16 (LP_NATIVE_VECTOR_WIDTH=512)" \
  LP_NATIVE_VECTOR_WIDTH=512 ctest --output-on-failure -j"$jobs" -L gpu "$@"
# The Catch2 binary with a tag filter (ctest has no labels for these tags): the curvature,
# the exact and fast filters and the saliency built on them, CPU only; on two processes
# (filters / the rest), as ctest -j would.
cpu_tags_a="[filter]~[gpu],[fast]~[gpu]"
cpu_tags_b="[curvature]~[gpu],[saliency]~[gpu],[cpu_dispatch]~[gpu],[exp_poly7]"
echo "== cpu saliency tests, baseline loops (MESHSAL_CPU_BASELINE=1)"
MESHSAL_CPU_BASELINE=1 ./meshsal_tests "$cpu_tags_a" > baseline_tests_a.log 2>&1 &
pid_a=$!
MESHSAL_CPU_BASELINE=1 ./meshsal_tests "$cpu_tags_b" > baseline_tests_b.log 2>&1 || { status=1; cat baseline_tests_b.log; }
wait "$pid_a" || { status=1; cat baseline_tests_a.log; }
tail -n 2 baseline_tests_a.log baseline_tests_b.log
exit "$status"
