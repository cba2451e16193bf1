#!/usr/bin/env bash
# Texel saving of `adaptex paint` (its defaults) on meshes the quality study has never seen, made in
# Blender from its primitives (make_meshes.py), with generated `lines` and `dots` at N:
#   bench/adapt/out_of_sample/out_of_sample.sh build/apps/cli/adaptex OUTDIR [N]
# For each case: PSNR of the default adaptive paint at N, of `--adapt none` at N, 2N and 4N (adaptex
# eval, 1M samples), and the texel saving factor: the texture area `none` needs to reach the adaptive
# PSNR, interpolated in log N (docs/quality.md). Needs Blender 3.4 (Debian `blender`) and python3.
set -euo pipefail
adaptex=$(realpath "${1:?usage: out_of_sample.sh ADAPTEX OUTDIR [N]}")
out=${2:?usage: out_of_sample.sh ADAPTEX OUTDIR [N]}
n=${3:-256}
here=$(dirname "$(realpath "$0")")
mkdir -p "$out" && cd "$out"
command -v blender >/dev/null || { echo "out_of_sample.sh: blender is not installed" >&2; exit 2; }
blender -b --factory-startup --python "$here/make_meshes.py" -- "$PWD" >blender.log 2>&1
psnr() { "$adaptex" eval "$1/$2.obj" "$1/$2.png" "$3" | python3 -c 'import json, sys; print(json.load(sys.stdin)["psnr"])'; }
echo "| mesh | kind | none N | adaptive N | none 2N | none 4N | texel saving |"
echo "|---|---|---:|---:|---:|---:|---:|"
for m in suzanne ico_holes torus_decim wavy_sheet; do
  for k in lines dots; do
    s=strokes_${m}_$k.json
    "$adaptex" strokes generate "$m.obj" --kind "$k" --seed 3 -o "$s" >/dev/null 2>&1
    "$adaptex" paint "$m.obj" --strokes "$s" --size "$n" -o "adapt_${m}_$k" >/dev/null 2>&1
    a=$(psnr "adapt_${m}_$k" "$m" "$s")
    p=()
    for size in "$n" $((2 * n)) $((4 * n)); do
      "$adaptex" paint "$m.obj" --strokes "$s" --size "$size" --adapt none -o "none_${m}_${k}_$size" >/dev/null 2>&1
      p+=("$(psnr "none_${m}_${k}_$size" "$m" "$s")")
    done
    python3 - "$m" "$k" "$a" "${p[@]}" <<'PY'
import sys
m, k, a, p = sys.argv[1], sys.argv[2], float(sys.argv[3]), [float(x) for x in sys.argv[4:7]]
if a <= p[0]:
    f = 1.0
elif a >= p[2]:
    f = 16.0  # at least 4N: reported as the bound
else:
    i = 0 if a <= p[1] else 1
    f = (2 ** (i + (a - p[i]) / (p[i + 1] - p[i]))) ** 2
print(f"| {m} | {k} | {p[0]:.2f} | {a:.2f} | {p[1]:.2f} | {p[2]:.2f} | {f:.2f} |")
PY
  done
done
