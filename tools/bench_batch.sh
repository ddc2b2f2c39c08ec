#!/usr/bin/env bash
# Benchmark of `meshsal batch` against one `meshsal saliency` process per model, over every
# mesh of ../shared/data/meshes except the igea_loop scans (or the folder given).
#   tools/bench_batch.sh [cpu|gpu|both] [DATA_DIR]
# cpu: batch --backend cpu against the sum of the single runs' saliency times ("seconds" of
#      saliency --json: the computation, without reading and writing) and of their whole
#      process times; the target is batch <= 1.1 x the saliency sum.
# gpu: batch --backend gpu (lavapipe when there is no GPU) against a shell loop of
#      saliency --backend gpu, each paying the Vulkan start-up and pipeline compilation;
#      the target is a speed-up of at least 1.5.
# Wall times from `date +%s.%N`; outputs go to a temporary folder, removed at the end.
set -euo pipefail
cd "$(dirname "$0")/.."
which="${1:-both}"
data="${2:-../shared/data/meshes}"
bin=build/meshsal
[ -x "$bin" ] || { echo "error: $bin is missing: run tools/setup.sh first" >&2; exit 1; }
[ -d "$data" ] || { echo "error: $data: no such folder" >&2; exit 1; }
meshes=()
for f in "$data"/*; do
  case "$(basename "$f")" in
    igea_loop*) continue ;;
    *.obj|*.ply|*.off|*.stl|*.obj.gz|*.ply.gz|*.off.gz|*.stl.gz) meshes+=("$f") ;;
  esac
done
[ "${#meshes[@]}" -gt 0 ] || { echo "error: $data: no mesh files" >&2; exit 1; }
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
now() { date +%s.%N; }
calc() { awk "BEGIN { printf \"%.6f\", $* }"; }
num() { sed -n "s/.*\"$1\": \([0-9.e+-]*\).*/\1/p"; }

bench() {  # bench BACKEND
  local backend="$1" loop_wall=0 sal_sum=0
  echo "== $backend: ${#meshes[@]} meshes"
  printf '%-24s %10s %10s\n' mesh "process_s" "saliency_s"
  for m in "${meshes[@]}"; do
    local t0 t1 json s
    t0=$(now)
    json=$("$bin" saliency "$m" -o "$tmp/single.ply" --backend "$backend" --json)
    t1=$(now)
    s=$(echo "$json" | num seconds)
    printf '%-24s %10.3f %10.3f\n' "$(basename "$m")" "$(calc "$t1 - $t0")" "$s"
    loop_wall=$(calc "$loop_wall + $t1 - $t0")
    sal_sum=$(calc "$sal_sum + $s")
  done
  rm -rf "$tmp/batch"
  local t0 t1 batch
  t0=$(now)
  "$bin" batch "${meshes[@]}" -o "$tmp/batch" --backend "$backend" -q
  t1=$(now)
  batch=$(calc "$t1 - $t0")
  printf 'shell loop of saliency:  %8.3f s (processes), %8.3f s (sum of saliency seconds)\n' "$loop_wall" "$sal_sum"
  printf 'batch:                   %8.3f s\n' "$batch"
  printf 'batch / saliency sum:    %8.3f   (cpu target <= 1.10)\n' "$(calc "$batch / $sal_sum")"
  printf 'loop / batch:            %8.3f   (gpu target >= 1.50)\n' "$(calc "$loop_wall / $batch")"
  grep -o '"device_opened": [a-z]*, "pipelines_built": [0-9]*' "$tmp/batch/batch.jsonl" | sort | uniq -c || true
}

case "$which" in
  cpu) bench cpu ;;
  gpu) bench gpu ;;
  both) bench cpu; bench gpu ;;
  *) echo "usage: tools/bench_batch.sh [cpu|gpu|both] [DATA_DIR]" >&2; exit 2 ;;
esac
