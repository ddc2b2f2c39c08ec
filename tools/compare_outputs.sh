#!/usr/bin/env bash
# Runs the same commands with two meshsal builds and compares every file they write, byte
# for byte: the check that a change leaves the outputs of the existing commands as they were,
# or the list of what differs.
#   tools/compare_outputs.sh OLD_MESHSAL NEW_MESHSAL [WORKDIR]
# Inputs: the shared meshes (../shared/data/meshes; skipped with a message when absent) and a
# GLB each build writes from one of them. Printed JSON is compared without its timings
# ("seconds", "*_seconds", "pairs_per_second", "peak_rss"), a page without the time its
# statistics give. Exits 1 when anything differs.
set -uo pipefail
cd "$(dirname "$0")/.."
old=${1:?usage: tools/compare_outputs.sh OLD_MESHSAL NEW_MESHSAL [WORKDIR]}
new=${2:?usage: tools/compare_outputs.sh OLD_MESHSAL NEW_MESHSAL [WORKDIR]}
work=${3:-$(mktemp -d /tmp/meshsal_compare.XXXXXX)}
data=$(cd ../shared/data/meshes 2>/dev/null && pwd || echo ../shared/data/meshes)
inputs=(bunny_3k.off spot_3k.obj fandisk_6k.obj bun_zipper_res3.ply max_planck_5k.obj)
for m in "${inputs[@]}"; do
  [ -f "$data/$m" ] || { echo "SKIPPED: $data/$m is absent"; exit 0; }
done

# Every command, one per line: IN and OUT stand for the input and the output folder.
commands() {
  cat <<'EOF'
saliency IN -o OUT/s.ply --backend cpu -q
saliency IN -o OUT/s.glb --backend cpu -q
saliency IN -o OUT/fast.ply --backend cpu --method fast --dump-scales -q
saliency IN -o OUT/ooc.ply --backend cpu --method fast --memory-limit 200M -q
simplify IN -o OUT/r.obj --ratio 0.2 --backend cpu -q
simplify IN -o OUT/r.ply --ratio 0.2 --backend cpu -q
simplify IN -o OUT/r.glb --ratio 0.2 --backend cpu -q
simplify IN -o OUT/none.obj --ratio 0.2 --weights none -q
simplify IN -o OUT/err.obj --target-error 0.5 --backend cpu -q
simplify IN -o OUT/tiles.ply --ratio 0.2 --tiles 3 --backend cpu -q
simplify IN -o OUT/ooc_simplified.ply --ratio 0.2 --memory-limit 200M --backend cpu -q
simplify IN -o OUT/lod.glb --lod 0.5,0.2 --backend cpu -q
simplify IN -o OUT/lod.obj --lod 0.5,0.2 --backend cpu -q
viewpoint IN --backend cpu --json
render IN -o OUT/best.png --best --backend cpu --size 128 -q
render IN -o OUT/angle.png --theta 30 --phi 10 --backend cpu --size 128 -q
view IN -o OUT/page.html --backend cpu -q
EOF
}

# Runs every command of one build into WORK/NAME/<input>/ (stdout kept as NNN.stdout), from
# inside WORK/NAME so that the names the outputs print are the same for both builds.
run_build() {
  local bin=$1 name=$2
  mkdir -p "$work/$name"
  (
    cd "$work/$name" || exit 1
    for m in "${inputs[@]}" glb; do
      local in="$data/$m" out="$m"
      mkdir -p "$out"
      if [ "$m" = glb ]; then
        "$bin" saliency "$data/spot_3k.obj" -o spot.glb --backend cpu -q
        in=spot.glb
      fi
      local i=0
      while read -r line; do
        i=$((i + 1))
        local cmd=${line//IN/$in}
        cmd=${cmd//OUT/$out}
        local base="$out/$(printf %03d $i)"
        # shellcheck disable=SC2086
        "$bin" $cmd > "$base.stdout" 2> "$base.stderr" || echo "exit $?" >> "$base.stdout"
        sed -i -E 's/"(seconds|[a-z_]*_seconds|pairs_per_second|peak_rss)": [0-9.e+-]+/"\1": T/g' "$base.stdout"
      done < <(commands)
      mkdir -p "$out/batch_in"
      cp "$in" "$out/batch_in/"
      "$bin" batch "$out/batch_in" -o "$out/batch" --simplify 0.2 --view --html --lod 0.5,0.2 --backend cpu --size 128 -q \
        > /dev/null 2>&1 || echo "batch exit $?" > "$out/batch.exit"
      rm -rf "$out/batch/.meshsal-batch" "$out/batch/batch.jsonl"
      # A page says how long its saliency took.
      find "$out" -name '*.html' -exec sed -i -E 's#<td>computed in</td><td>[0-9.e+-]+ s</td>#<td>computed in</td><td>T</td>#' {} +
    done
  )
}

run_build "$old" old
run_build "$new" new
status=0
while read -r f; do
  rel=${f#"$work/old/"}
  case "$rel" in *.stderr) continue ;; esac
  if [ ! -f "$work/new/$rel" ]; then
    echo "only before: $rel"; status=1
  elif ! cmp -s "$f" "$work/new/$rel"; then
    echo "differs:     $rel"; status=1
  fi
done < <(find "$work/old" -type f | sort)
while read -r f; do
  rel=${f#"$work/new/"}
  case "$rel" in *.stderr) continue ;; esac
  [ -f "$work/old/$rel" ] || { echo "only after:  $rel"; status=1; }
done < <(find "$work/new" -type f | sort)
echo "outputs in $work (old/ and new/; each command's stderr beside its stdout)"
exit $status
