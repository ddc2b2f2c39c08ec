#!/usr/bin/env bash
# The layering, checked on the built libraries (ctest: layers). Usage: check_layers.sh BUILD_DIR CXX
#  1. Links: every meshsal symbol a layer's library uses is defined in that library or in
#     one of the layers it may use (BUILD_DIR/layers.txt, written by CMakeLists.txt). A call
#     upwards (or sideways) would be an undefined symbol of a layer below.
#  2. Includes: a file of the saliency layer that includes a view header does not compile
#     with the saliency layer's include root, and does with the view layer's (so the
#     refusal is the root's doing, not a broken probe).
set -euo pipefail
build=$1 cxx=$2
fail() { echo "FAIL: $*" >&2; exit 1; }
cd "$build"
[ -s layers.txt ] || fail "no layers.txt in $build"

defined() {  # defined LIB...: the meshsal symbols those archives define
  for lib in "$@"; do nm -C --defined-only "$lib" 2>/dev/null; done |
    awk '$2 ~ /^[TtWwVvDdBbRru]$/ { $1 = ""; $2 = ""; print substr($0, 3) }' | grep '^meshsal::' | sort -u
}
undefined() {  # undefined LIB: the meshsal symbols that archive uses and does not define
  nm -C --undefined-only "$1" 2>/dev/null | awk '{ $1 = ""; print substr($0, 2) }' | grep '^meshsal::' | sort -u
}

checked=0
while IFS=: read -r lib allowed; do
  [ -f "$lib" ] || fail "$lib is not built"
  libs=("$lib")
  for dep in $allowed; do libs+=("$dep"); done
  missing=$(comm -23 <(undefined "$lib") <(defined "${libs[@]}"))
  # A symbol a layer uses must come from it or from below; one defined nowhere at all is the
  # C++ library's (inline, templates) and is no layering question.
  upward=""
  while IFS= read -r sym; do
    [ -n "$sym" ] || continue
    if grep -qxF -- "$sym" <(defined libmeshsal_*.a); then upward+="$sym"$'\n'; fi
  done <<<"$missing"
  [ -z "$upward" ] || fail "$lib uses symbols of a layer it may not use:"$'\n'"$upward"
  echo "ok: $lib uses only itself and:${allowed:- nothing}"
  checked=$((checked + 1))
done <layers.txt
[ "$checked" -ge 6 ] || fail "only $checked libraries checked"

probe=$(mktemp --suffix=.cpp)
trap 'rm -f "$probe"' EXIT
printf '#include "view/camera.h"\nint main() { return 0; }\n' >"$probe"
src=$(cd "$(dirname "$0")/../.." && pwd)
if "$cxx" -std=c++17 -fsyntax-only -I"$src/include" -I"$build/layer_include/saliency" "$probe" 2>/dev/null; then
  fail "a saliency file could include view/camera.h"
fi
"$cxx" -std=c++17 -fsyntax-only -I"$src/include" -I"$build/layer_include/view" "$probe" ||
  fail "the probe does not compile even with the view layer's root"
echo "ok: the saliency layer cannot include view/camera.h; the view layer can"
