#!/usr/bin/env bash
# Frame time while orbiting and dab-to-screen latency while painting, for adaptex-studio under Xvfb
# with Mesa's software OpenGL (llvmpipe). Usage:
#   [HISTORY=N] [SIZE=S] bench/studio/measure_studio.sh BUILD_DIR [MESH...]
#   (default: every mesh in ../shared/meshes). HISTORY=N: before the drags, the app replays N generated
#   `mixed` strokes (adaptex strokes generate, seed 1) and waits until adaptation has settled on them,
#   so the drags are painted on a long history. SIZE: the texture size (default: the studio's).
# Prints one JSON line per measurement: the app's --stats output with the mesh and the kind
# (orbit | paint-none | paint-two-stage | paint-density-flow; density-flow is the default). Runs itself inside xvfb-run when DISPLAY is unset.
set -euo pipefail
if [ -z "${DISPLAY:-}" ]; then
  command -v xvfb-run >/dev/null || { echo "xvfb-run missing" >&2; exit 77; }
  exec xvfb-run -a -s "-screen 0 1280x800x24" "$0" "$@"
fi
command -v xdotool >/dev/null || { echo "xdotool missing" >&2; exit 77; }
BUILD=${1:?usage: measure_studio.sh BUILD_DIR [MESH...]}
shift
STUDIO="$BUILD/apps/studio/adaptex-studio"
HERE=$(cd "$(dirname "$0")" && pwd)
MESHES=("$@")
if [ ${#MESHES[@]} -eq 0 ]; then MESHES=("$HERE"/../../../shared/meshes/*.{obj,off,ply}); fi
export LIBGL_ALWAYS_SOFTWARE=1
TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT
COMMON=(--window 1280x800 --no-vsync --no-recovery --config-dir "$TMP/cfg")
[ -n "${SIZE:-}" ] && COMMON+=(--texture-size "$SIZE")
for mesh in "${MESHES[@]}"; do
  name=$(basename "$mesh")
  REPLAY=()
  if [ "${HISTORY:-0}" -gt 0 ]; then
    "$BUILD/apps/cli/adaptex" strokes generate "$mesh" --kind mixed --seed 1 --count "$HISTORY" -o "$TMP/h.json" >/dev/null
    REPLAY=(--replay "$TMP/h.json")
  fi
  # 1. Orbit: 200 frames at 1280x800 with the panels shown (glFinish every frame).
  timeout 900 "$STUDIO" "$mesh" "${COMMON[@]}" --orbit-frames 200 --stats "$TMP/s.json" >/dev/null 2>&1 || true
  [ -f "$TMP/s.json" ] && echo "{\"mesh\":\"$name\",\"kind\":\"orbit\",\"stats\":$(tr -d '\n' < "$TMP/s.json")}"
  rm -f "$TMP/s.json"
  # 2. Painting: real xdotool drags across the model; then with two-stage and density-flow adaptation.
  for adapt in none two-stage density-flow; do
    "$STUDIO" "$mesh" "${COMMON[@]}" "${REPLAY[@]}" --adapt "$adapt" --stats "$TMP/s.json" > "$TMP/app.log" 2>&1 &
    pid=$!
    for _ in $(seq 1200); do grep -q "adaptex-studio: ready" "$TMP/app.log" && break; sleep 0.5; done
    xdotool mousemove 560 400 sleep 0.3 mousedown 1 sleep 0.1
    for x in $(seq 570 6 760); do xdotool mousemove "$x" $((400 + (x - 560) / 6)) sleep 0.02; done
    xdotool mouseup 1 sleep 0.2 mousemove 700 330 mousedown 1 sleep 0.1
    for x in $(seq 700 -6 520); do xdotool mousemove "$x" 330 sleep 0.02; done
    xdotool mouseup 1 sleep 3
    kill -TERM "$pid"
    wait "$pid" || true
    [ -f "$TMP/s.json" ] && echo "{\"mesh\":\"$name\",\"kind\":\"paint-$adapt\",\"stats\":$(tr -d '\n' < "$TMP/s.json")}"
    rm -f "$TMP/s.json"
  done
done
