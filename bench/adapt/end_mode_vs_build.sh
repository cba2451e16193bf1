#!/usr/bin/env bash
# End-mode re-parameterization time of two adaptex builds, as `adaptex paint` runs it with its defaults:
#   bench/adapt/end_mode_vs_build.sh [--equal-quality] OLD_ADAPTEX NEW_ADAPTEX MESH_DIR OUT.txt [REPEATS]
# For 9 shared meshes x generated `mixed` / `dots` (seed 1), each build runs `adaptex paint` REPEATS
# times (default 3), the two builds alternating; every run appends one line to OUT.txt:
# - same size (default): both builds at 256² and 1024²;
#   "mesh kind N repeat old|new reparam_ms total_s";
# - --equal-quality: OLD at 2N against NEW at N (N = 256, 1024), and NEW's `adaptex eval` of each
#   exported OBJ + PNG (300,000 samples): "mesh kind N repeat old|new reparam_ms psnr" (N = NEW's
#   size; OLD ran at 2N). NEW at N reaches about the PSNR OLD reaches at 2N, so this compares the
#   time to reach a given quality.
# reparam_ms is report.json's adapt.reparameterizations.total_ms (wall time of the end-mode
# re-parameterization), total_s the whole command's. The stroke files come from NEW's `strokes
# generate` (the file format is a contract, so an older build reads them too). Used in
# docs/benchmarks.md, "End mode against the thesis-relaxation build"; the medians per case:
# python3 bench/adapt/end_mode_vs_build.py OUT.txt
set -euo pipefail
equal_quality=0
if [ "${1:-}" = --equal-quality ]; then
  equal_quality=1
  shift
fi
usage="usage: end_mode_vs_build.sh [--equal-quality] OLD NEW MESH_DIR OUT [REPEATS]"
old=$(realpath "${1:?$usage}")
new=$(realpath "${2:?$usage}")
meshes=$(realpath "${3:?$usage}")
out=$(realpath -m "${4:?$usage}")
repeats=${5:-3}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"
# Lines go to a file in the work directory and reach OUT only when every run has finished (a failed
# run leaves no partial OUT behind).
lines="$work/lines.txt"
: > "$lines"
for m in venus.off spot.obj triceratops.off dino.off kitten.obj fandisk.off camelhead.off face.obj bunny.ply; do
  s=${m%.*}
  for k in mixed dots; do
    "$new" strokes generate "$meshes/$m" --kind "$k" --seed 1 -o "${s}_$k.json" > /dev/null
    for n in 256 1024; do
      for r in $(seq "$repeats"); do
        for b in old new; do
          bin=$old
          size=$n
          [ "$b" = new ] && bin=$new
          [ "$b" = old ] && [ "$equal_quality" = 1 ] && size=$((2 * n))
          rm -rf run
          "$bin" paint "$meshes/$m" --strokes "${s}_$k.json" --size "$size" -o run > /dev/null 2>&1
          t=$(python3 -c "import json; print(json.load(open('run/report.json'))['adapt']['reparameterizations']['total_ms'])")
          if [ "$equal_quality" = 1 ]; then
            x=$("$new" eval "run/$s.obj" "run/$s.png" "${s}_$k.json" --samples 300000 |
                python3 -c "import json, sys; print(json.load(sys.stdin)['psnr'])")
          else
            x=$(python3 -c "import json; print(json.load(open('run/report.json'))['times_s']['total'])")
          fi
          echo "$s $k $n $r $b $t $x" >> "$lines"
        done
      done
    done
  done
done
mv "$lines" "$out"
