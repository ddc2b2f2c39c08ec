#!/usr/bin/env bash
# The installed CMake package, used from outside the tree (ctest: package_consumer).
#  1. installs this build (with Vulkan) into a temporary prefix and builds
#     tests/package/consumer against meshsal::core and meshsal::gpu, then runs both;
#  2. configures a CPU-only meshsal (MESHSAL_WITH_VULKAN=OFF, Vulkan hidden from CMake),
#     checks that its tool links no Vulkan and refuses --backend gpu clearly, installs it
#     and builds the consumer against that package too.
# Usage: run.sh SOURCE_DIR BUILD_DIR
set -euo pipefail
src=$1 build=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }
expect() {  # expect NAME OUTPUT PATTERN
  grep -Eq "$3" <<<"$2" || fail "$1 printed '$2', expected /$3/"
  echo "ok: $1: $2"
}

cmake --install "$build" --prefix "$work/full" >/dev/null
[ -f "$work/full/include/meshsal/meshsal.h" ] || fail "public header not installed"
# The public headers are meshsal.h and its parts, every file of include/meshsal/: all of
# them installed, and nothing else (no internal header).
installed=$(cd "$work/full/include" && find . -name '*.h' | sort)
public=$(cd "$src/include" && find . -name '*.h' | sort)
[ "$installed" = "$public" ] || fail "installed headers differ from include/: $(diff <(echo "$public") <(echo "$installed") | tr '\n' ' ')"
# Each installed header compiles alone from the installed include folder.
for h in $installed; do
  echo "#include <${h#./}>" | c++ -std=c++17 -fsyntax-only -x c++ -I"$work/full/include" - ||
    fail "installed ${h#./} does not compile alone"
done
echo "ok: $(wc -w <<<"$installed") public headers installed, each compiles alone"
cmake -S "$src/tests/package/consumer" -B "$work/consumer-full" -DCMAKE_PREFIX_PATH="$work/full" >/dev/null
cmake --build "$work/consumer-full" -j2 >/dev/null
expect "core, cpu" "$("$work/consumer-full/consumer_core")" '^vulkan=0 backend=cpu .*pairs=[1-9].* faces=6 image=32x32$'
expect "core, gpu" "$("$work/consumer-full/consumer_core" gpu || true)" 'built without Vulkan'
expect "gpu, cpu" "$("$work/consumer-full/consumer_gpu")" '^vulkan=1 backend=cpu .* faces=6 image=32x32$'
expect "gpu, gpu" "$("$work/consumer-full/consumer_gpu" gpu)" '^vulkan=1 backend=[^c].*pairs=[1-9].* faces=6 image=32x32$'

cmake -S "$src" -B "$work/cpu-only" -DCMAKE_BUILD_TYPE=Release -DMESHSAL_WITH_VULKAN=OFF \
  -DMESHSAL_BUILD_TESTS=OFF -DCMAKE_DISABLE_FIND_PACKAGE_Vulkan=ON >/dev/null
cmake --build "$work/cpu-only" -j2 --target meshsal_cli >/dev/null
! ldd "$work/cpu-only/meshsal" | grep -qi vulkan || fail "the CPU-only tool links Vulkan"
printf 'OFF\n4 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n' >"$work/tet.off"
msg=$("$work/cpu-only/meshsal" saliency "$work/tet.off" -o "$work/tet.ply" --backend gpu 2>&1 || true)
expect "cpu-only tool, --backend gpu" "$msg" 'built without Vulkan'
"$work/cpu-only/meshsal" saliency "$work/tet.off" -o "$work/tet.ply" -q || fail "CPU-only saliency failed"
cmake --install "$work/cpu-only" --prefix "$work/cpu" >/dev/null
cmake -S "$src/tests/package/consumer" -B "$work/consumer-cpu" -DCMAKE_PREFIX_PATH="$work/cpu" >/dev/null
cmake --build "$work/consumer-cpu" -j2 >/dev/null
[ ! -e "$work/consumer-cpu/consumer_gpu" ] || fail "a CPU-only package offers meshsal::gpu"
expect "cpu-only package" "$("$work/consumer-cpu/consumer_core")" '^vulkan=0 backend=cpu .* faces=6 image=32x32$'
echo "package consumer: all checks passed"
