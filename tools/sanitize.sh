#!/usr/bin/env bash
# Builds the library, the command line, the tests and the Python module with
# AddressSanitizer and UndefinedBehaviorSanitizer (-DMESHSAL_SANITIZE=ON) into
# build-sanitize/ and runs the whole suite there, lavapipe, the Khronos validation layer and
# the Python tests included.
#   tools/sanitize.sh [CTEST ARGS...]      e.g. tools/sanitize.sh -R '\[io\]'
# Any sanitizer report aborts the test that triggered it, so a clean run is a passing run.
# Leaks are checked too, except those reported inside the Vulkan loader, lavapipe, LLVM
# and the validation layer: uninstrumented driver code that keeps global state for the
# process's lifetime (tools/lsan.supp). Expect ~3x the normal suite's time.
set -euo pipefail
cd "$(dirname "$0")/.."
tools/setup.sh >/dev/null   # packages (and the normal build)
cmake -S . -B build-sanitize -DCMAKE_BUILD_TYPE=RelWithDebInfo -DMESHSAL_SANITIZE=ON -DMESHSAL_BUILD_PYTHON=ON >/dev/null
cmake --build build-sanitize -j"$(nproc)"
export ASAN_OPTIONS=${ASAN_OPTIONS:-abort_on_error=1:detect_leaks=1:strict_string_checks=1:detect_stack_use_after_return=1}
export LSAN_OPTIONS=${LSAN_OPTIONS:-suppressions=$PWD/tools/lsan.supp:print_suppressions=0}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
# lavapipe leaks an allocation (128 bytes) in its own code, and the Vulkan loader unloads it
# when the instance goes: by exit its frames are an "<unknown module>" that no suppression
# can name (seen with Mesa 22.3.6-1+deb12u2). Preloading it keeps it mapped, so its leaks
# are suppressed like the rest of the driver. Only the driver is preloaded (ASan's runtime
# would turn every uninstrumented helper a test runs, `script`, `sh`, into a leak check), so
# ASan is told not to insist on coming first: the driver defines nothing ASan intercepts.
lvp=$(ls /usr/lib/*/libvulkan_lvp.so 2>/dev/null | head -n 1 || true)
if [ -n "$lvp" ]; then
  export LD_PRELOAD="$lvp${LD_PRELOAD:+ $LD_PRELOAD}"
  export ASAN_OPTIONS="$ASAN_OPTIONS:verify_asan_link_order=0"
fi
cd build-sanitize
# package_consumer builds a plain (unsanitized) meshsal from source: nothing to check here.
rc=0
ctest --output-on-failure -j"$(nproc)" --timeout 1200 -E package_consumer -LE 'mpi|python' "$@" || rc=1
# Open MPI's components (loaded and unloaded by MPI_Init/MPI_Finalize) keep allocations
# they never free, in modules gone by exit that no suppression can name: the mpirun tests
# run with every check but the leak check.
ASAN_OPTIONS="$ASAN_OPTIONS:detect_leaks=0" \
  ctest --output-on-failure -j"$(nproc)" --timeout 1200 -E package_consumer -L mpi "$@" || rc=1
# The Python module, built with the sanitizers too: python3 itself is not, so their
# runtimes are preloaded ahead of everything (ASan must come first), and the leak check is
# off (the interpreter keeps its allocations until exit by design).
asan=$(gcc -print-file-name=libasan.so) ubsan=$(gcc -print-file-name=libubsan.so)
LD_PRELOAD="$asan $ubsan${LD_PRELOAD:+ $LD_PRELOAD}" ASAN_OPTIONS="$ASAN_OPTIONS:detect_leaks=0" \
  ctest --output-on-failure --timeout 1200 -L python "$@" || rc=1
exit $rc
