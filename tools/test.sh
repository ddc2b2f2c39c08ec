#!/usr/bin/env bash
# Sets up (packages + build) if needed, then runs the whole test suite through ctest, and
# the Vulkan tests (label gpu) three more times: on the discrete-GPU memory path (device-
# local buffers, transfers through the staging area) and at lavapipe's other subgroup sizes
# (LP_NATIVE_VECTOR_WIDTH=128: 4 lanes, 512: 16 lanes; the default, 256, gives 8), and
# the whole suite once more on the baseline x86-64 loops (MESHSAL_CPU_BASELINE=1; the
# first run takes the AVX2 ones where the CPU has AVX2: README "Portable build").
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
# The whole suite once more on the baseline x86-64 loops (but the installed-package test,
# which builds meshsal again and has no CPU loops of its own): about 2 minutes here.
run "all tests, baseline CPU loops (MESHSAL_CPU_BASELINE=1)" \
  MESHSAL_CPU_BASELINE=1 ctest --output-on-failure -j"$jobs" -E '^package_consumer$' "$@"
exit "$status"
