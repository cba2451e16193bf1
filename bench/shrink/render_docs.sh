#!/usr/bin/env bash
# The renders of docs/assets.md ("Renders"), made anew: original / downsized / adaptex for three
# assets at 256², close-ups at 256², and spot's black patch at 128². Needs the assets
# (get_assets.sh), a build with adaptex and adaptex_asset_eval, Blender and ImageMagick.
#
#   bench/shrink/render_docs.sh [-b BUILD] [-a ASSETS] [OUTDIR]     (default OUTDIR: docs/images)
set -euo pipefail
HERE=$(cd "$(dirname "$0")" && pwd)
BUILD=$HERE/../../build ASSETS=/work/assets
while getopts b:a: opt; do
  case $opt in
    b) BUILD=$OPTARG ;; a) ASSETS=$OPTARG ;; *) exit 2 ;;
  esac
done
shift $((OPTIND - 1))
OUT=${1:-$HERE/../../docs/images}
work=$(mktemp -d /tmp/adaptex-render-docs-XXXXXX)
trap 'rm -rf "$work"' EXIT
render() { "$HERE/render_compare.sh" -b "$BUILD" -a "$ASSETS" -p 256 "$@" > /dev/null; }
# name size view: whole models, then close-ups (eyes and nose; chest and mouth; the patch's edge).
render african_head 256 0,0,1.9,0,0.15 "$work/head.png"
render diablo3_pose 256 0,5,2.4,0,0.3 "$work/diablo.png"
render spot 256 -140,10,1.3 "$work/spot.png"
render african_head 256 0,0,4.5,0,0.22 "$work/head_c.png"
render diablo3_pose 256 0,5,6,0.02,0.3 "$work/diablo_c.png"
render spot 256 -140,5,5,-0.1,0.05 "$work/spot_c.png"
render spot 128 -140,5,5,-0.1,0.05 "$work/spot_c128.png"
mkdir -p "$OUT"
convert "$work/head.png" "$work/diablo.png" "$work/spot.png" -append "$OUT/assets-256.png"
convert "$work/head_c.png" "$work/diablo_c.png" "$work/spot_c.png" -append "$OUT/assets-closeup-256.png"
cp "$work/spot_c128.png" "$OUT/assets-closeup-128-spot.png"
echo "wrote $OUT/assets-256.png, assets-closeup-256.png, assets-closeup-128-spot.png"
