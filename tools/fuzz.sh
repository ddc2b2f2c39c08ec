#!/usr/bin/env bash
# Fuzzes the loaders (and the ground-truth rows of meshsal eval) with libFuzzer (a pre-submit tool, not part of CI).
#   tools/fuzz.sh [SECONDS] [TARGET...]     targets: obj off ply stl gltf glb gz saliency plystream rows (default: all)
# Builds tests/fuzz/fuzz_*.cpp with clang, AddressSanitizer and UndefinedBehaviorSanitizer
# into build-fuzz/ (-DMESHSAL_FUZZ=ON) and runs each target for SECONDS (default 60) from
# its seed corpus tests/fuzz/corpus/TARGET (new inputs go to build-fuzz/corpus/TARGET, not
# into the repository). A crash, sanitizer report, leak, time-out (2 s) or memory blow-up
# (2 GB) stops that target and leaves the input in build-fuzz/findings/TARGET/. Fix it,
# then copy the file into tests/fuzz/regressions/TARGET/: the normal suite replays every
# file there (tests/io/test_fuzz_replay.cpp). Exits 1 when any target found something.
set -euo pipefail
cd "$(dirname "$0")/.."
SECONDS_EACH=${1:-60}
shift || true
TARGETS=("$@")
[ ${#TARGETS[@]} -eq 0 ] && TARGETS=(obj off ply stl gltf glb gz saliency plystream rows)

# clang 14 with libFuzzer's runtime (Debian 12: clang, libclang-rt-14-dev); only this
# script needs them, so they are installed here rather than by tools/setup.sh.
if ! command -v clang++ >/dev/null || [ ! -f "$(clang++ -print-file-name=libclang_rt.fuzzer-x86_64.a)" ]; then
  SUDO=""; [ "$(id -u)" -ne 0 ] && SUDO="sudo"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq clang libclang-rt-14-dev
fi

cmake -S . -B build-fuzz -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_COMPILER=clang++ -DMESHSAL_FUZZ=ON >/dev/null
cmake --build build-fuzz -j"$(nproc)" --target "${TARGETS[@]/#/fuzz_}"

export ASAN_OPTIONS=${ASAN_OPTIONS:-abort_on_error=1:detect_leaks=1}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
status=0
for t in "${TARGETS[@]}"; do
  mkdir -p "build-fuzz/corpus/$t" "build-fuzz/findings/$t"
  echo "== fuzz_$t for ${SECONDS_EACH}s"
  # libFuzzer exits at once on a corpus folder that does not exist: pass only those that do
  # (not every target has regression files yet).
  corpora=("build-fuzz/corpus/$t")
  for d in "tests/fuzz/corpus/$t" "tests/fuzz/regressions/$t"; do
    [ -d "$d" ] && corpora+=("$d")
  done
  if ! build-fuzz/fuzz_"$t" -max_total_time="$SECONDS_EACH" -timeout=2 -rss_limit_mb=2048 -max_len=65536 \
      -print_final_stats=1 -artifact_prefix="build-fuzz/findings/$t/" \
      "${corpora[@]}" 2>"build-fuzz/fuzz_$t.log"; then
    echo "fuzz_$t: FOUND SOMETHING, see build-fuzz/fuzz_$t.log and build-fuzz/findings/$t/"
    status=1
  fi
  grep -E "^stat::(number_of_executed_units|new_units_added)|^#.*DONE" "build-fuzz/fuzz_$t.log" || true
done
exit $status
