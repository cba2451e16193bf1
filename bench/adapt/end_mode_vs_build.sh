#!/usr/bin/env bash
# End-mode re-parameterization time of two adaptex builds, as `adaptex paint` runs it with its defaults:
#   bench/adapt/end_mode_vs_build.sh OLD_ADAPTEX NEW_ADAPTEX MESH_DIR OUT.txt [REPEATS]
# For 9 shared meshes x generated `mixed` / `dots` (seed 1) x 256² / 1024², each build runs
# `adaptex paint` REPEATS times (default 3), the two builds alternating; every run appends
# "mesh kind N repeat old|new reparam_ms total_s" to OUT.txt: reparam_ms is report.json's
# adapt.reparameterizations.total_ms (wall time of the end-mode re-parameterization), total_s the
# whole command's. The stroke files come from NEW's `strokes generate` (the file format is a contract,
# so an older build reads them too). Used in docs/benchmarks.md, "End mode against the build issue 12
# was filed on"; the medians per case: python3 bench/adapt/end_mode_vs_build.py OUT.txt
set -euo pipefail
old=$(realpath "${1:?usage: end_mode_vs_build.sh OLD NEW MESH_DIR OUT [REPEATS]}")
new=$(realpath "${2:?usage: end_mode_vs_build.sh OLD NEW MESH_DIR OUT [REPEATS]}")
meshes=$(realpath "${3:?usage: end_mode_vs_build.sh OLD NEW MESH_DIR OUT [REPEATS]}")
out=$(realpath -m "${4:?usage: end_mode_vs_build.sh OLD NEW MESH_DIR OUT [REPEATS]}")
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
          [ "$b" = new ] && bin=$new
          rm -rf run
          "$bin" paint "$meshes/$m" --strokes "${s}_$k.json" --size "$n" -o run > /dev/null 2>&1
          t=$(python3 -c "import json; r = json.load(open('run/report.json')); print(r['adapt']['reparameterizations']['total_ms'], r['times_s']['total'])")
          echo "$s $k $n $r $b $t" >> "$lines"
        done
      done
    done
  done
done
mv "$lines" "$out"
