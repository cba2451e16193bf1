#!/usr/bin/env bash
# Original / plain downsizing / adaptex, side by side at equal size, for one asset of docs/assets.md:
#
#   bench/shrink/render_compare.sh [-b BUILD] [-a ASSETS] [-c shrink|reparam] [-p PX] NAME N VIEW OUT.png
#
# N: the texture size of the downsized and adapted results; VIEW: AZIMUTH,ELEVATION,ZOOM[,DX,DY] of
# render_assets.py (e.g. 0,0,1 front; 0,5,3,0,0.2 a close-up); PX: pixels per panel (default 512).
# The adaptex result is `adaptex shrink MESH --size N` (default when the CLI has it) or `adaptex
# reparam MESH TEXTURE --size N`; it is kept in OUT.png's folder as NAME_N_<command>/. Renders by
# Blender (Cycles on the CPU, unlit texture colour, bilinear, clamped), about 10 s a panel.
set -euo pipefail
HERE=$(cd "$(dirname "$0")" && pwd)
BUILD=$HERE/../../build ASSETS=/work/assets CMD="" PX=512
while getopts b:a:c:p: opt; do
  case $opt in
    b) BUILD=$OPTARG ;; a) ASSETS=$OPTARG ;; c) CMD=$OPTARG ;; p) PX=$OPTARG ;;
    *) exit 2 ;;
  esac
done
shift $((OPTIND - 1))
[[ $# == 4 ]] || { echo "usage: $0 [-b BUILD] [-a ASSETS] [-c shrink|reparam] [-p PX] NAME N VIEW OUT.png" >&2; exit 2; }
name=$1 n=$2 view=$3 out=$4
ADAPTEX=$BUILD/apps/cli/adaptex
e=$ASSETS/$name/eval
if [[ -z $CMD ]]; then
  CMD=reparam
  "$ADAPTEX" --help | grep -qE "^ +shrink " && CMD=shrink
fi
work=$(dirname "$out")/${name}_${n}_$CMD
rm -rf "$work"
if [[ $CMD == shrink ]]; then
  "$ADAPTEX" -q shrink "$e/mesh.obj" --size "$n" -o "$work" > /dev/null
else
  "$ADAPTEX" -q reparam "$e/mesh.obj" "$e/diffuse.png" --size "$n" -o "$work"
fi
obj=$(find "$work" -maxdepth 1 -name '*.obj' | head -1)
tex=$(dirname "$obj")/$(awk '/^map_Kd /{print $NF; exit}' "$(dirname "$obj")/$(awk '/^mtllib /{print $2; exit}' "$obj")")
"$BUILD/bench/shrink/adaptex_asset_eval" downsize "$e/diffuse.png" "$n" "$work/downsized.png"
blender -b --factory-startup --python "$HERE/render_assets.py" -- "$out" \
  "original=$e/mesh.obj,$e/diffuse.png" "downsized=$e/mesh.obj,$work/downsized.png" "$CMD=$obj,$tex" \
  --size "$PX" --view "$view" | grep -E "^wrote"
