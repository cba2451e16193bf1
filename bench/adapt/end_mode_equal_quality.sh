#!/usr/bin/env bash
# End mode at equal quality: a build at 2N against another at N, time and PSNR, as `adaptex paint` runs
# them with their defaults:
#   bench/adapt/end_mode_equal_quality.sh OLD_ADAPTEX NEW_ADAPTEX MESH_DIR OUT.txt
# For 9 shared meshes x generated `mixed` / `dots` (seed 1): OLD at 512² and 2048², NEW at 256² and
# 1024², one run each. Every run appends "mesh kind old|new N reparam_ms psnr" to OUT.txt: reparam_ms
# is report.json's adapt.reparameterizations.total_ms, psnr NEW's `adaptex eval` of the exported
# OBJ + PNG against the stroke file (300,000 samples). Used in docs/benchmarks.md, "End mode against
# the build issue 12 was filed on", session 16 (issue 12 compares the same N; this compares equal
# quality: NEW at N reaches about what OLD reaches at 2N).
set -euo pipefail
old=$(realpath "${1:?usage: end_mode_equal_quality.sh OLD NEW MESH_DIR OUT}")
new=$(realpath "${2:?usage: end_mode_equal_quality.sh OLD NEW MESH_DIR OUT}")
meshes=$(realpath "${3:?usage: end_mode_equal_quality.sh OLD NEW MESH_DIR OUT}")
out=$(realpath -m "${4:?usage: end_mode_equal_quality.sh OLD NEW MESH_DIR OUT}")
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"
lines="$work/lines.txt"
: > "$lines"
for m in venus.off spot.obj triceratops.off dino.off kitten.obj fandisk.off camelhead.off face.obj bunny.ply; do
  s=${m%.*}
  for k in mixed dots; do
    "$new" strokes generate "$meshes/$m" --kind "$k" --seed 1 -o "${s}_$k.json" > /dev/null
    for cfg in "old 512" "new 256" "old 2048" "new 1024"; do
      read -r b n <<< "$cfg"
      bin=$old
      [ "$b" = new ] && bin=$new
      rm -rf run
      "$bin" paint "$meshes/$m" --strokes "${s}_$k.json" --size "$n" -o run > /dev/null 2>&1
      t=$(python3 -c "import json; print(json.load(open('run/report.json'))['adapt']['reparameterizations']['total_ms'])")
      p=$("$new" eval "run/$s.obj" "run/$s.png" "${s}_$k.json" --samples 300000 |
          python3 -c "import json, sys; print(json.load(sys.stdin)['psnr'])")
      echo "$s $k $b $n $t $p" >> "$lines"
    done
  done
done
mv "$lines" "$out"
