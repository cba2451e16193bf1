#!/usr/bin/env bash
# The table of docs/assets.md: for every asset laid out by get_assets.sh (ASSETS/NAME/eval) and every
# size, the surface PSNR (paint/asset_eval.h, 200k samples, seed 1) against the original texture of
#   - plain downsizing: the artist's UVs, the texture box-downsized to N² (what a user does without adaptex),
#   - `adaptex reparam MESH TEXTURE --size N` (resample path),
#   - `adaptex shrink MESH --size N` when the CLI has that command,
# each result's gain over downsizing and its texel saving factor (texels downsizing needs to match it,
# from downsizing to N/2 .. < native in sqrt(2) steps, PSNR linear in log texels, / the result's texels).
#
#   bench/shrink/asset_table.sh [-b BUILD] [-a ASSETS] [-o OUT] [-s "256 128"] [-n "spot fuze"]
# Prints two Markdown tables (PSNR, gain, saving; faces, flips, degenerate UV faces and shared texels of
# every result against its input) and writes OUT/table.jsonl (one JSON line per asset and size); every
# command's output stays in OUT/NAME_N_{reparam,shrink}/ with its log.
set -euo pipefail
HERE=$(cd "$(dirname "$0")" && pwd)
BUILD=$HERE/../../build ASSETS=/work/assets OUT=/tmp/adaptex_asset_table SIZES="256 128" NAMES=""
while getopts b:a:o:s:n: opt; do
  case $opt in
    b) BUILD=$OPTARG ;; a) ASSETS=$OPTARG ;; o) OUT=$OPTARG ;; s) SIZES=$OPTARG ;; n) NAMES=$OPTARG ;;
    *) echo "usage: $0 [-b BUILD] [-a ASSETS] [-o OUT] [-s SIZES] [-n NAMES]" >&2; exit 2 ;;
  esac
done
ADAPTEX=$BUILD/apps/cli/adaptex
EVAL=$BUILD/bench/shrink/adaptex_asset_eval
for b in "$ADAPTEX" "$EVAL"; do [[ -x $b ]] || { echo "asset_table.sh: $b is not built" >&2; exit 2; }; done
[[ -n $NAMES ]] || NAMES=$(cd "$ASSETS" && for d in */eval; do echo "${d%/eval}"; done)
HAVE_SHRINK=0
"$ADAPTEX" --help | grep -qE "^ +shrink " && HAVE_SHRINK=1
mkdir -p "$OUT"
: > "$OUT/table.jsonl"

# result DIR: "OBJ,TEXTURE" of the OBJ a command wrote into DIR (texture = its MTL's map_Kd).
result() {
  local obj mtl tex
  obj=$(find "$1" -maxdepth 1 -name '*.obj' | head -1)
  [[ -n $obj ]] || return 1
  mtl=$(dirname "$obj")/$(awk '/^mtllib /{print $2; exit}' "$obj")
  tex=$(dirname "$obj")/$(awk '/^map_Kd /{print $NF; exit}' "$mtl")
  echo "$obj,$tex"
}
# run NAME LOGDIR CMD...: run a command, keep its log; print the test spec on success.
run() {
  local name=$1 dir=$2
  shift 2
  rm -rf "$dir"
  if "$@" -o "$dir" > "$dir.log" 2>&1 && spec=$(result "$dir"); then echo "--test $name=$spec"; else
    echo "asset_table.sh: $name failed: $(grep -v '^ *$' "$dir.log" | tail -1)" >&2; fi
}

for name in $NAMES; do
  e=$ASSETS/$name/eval
  for n in $SIZES; do
    tests=$(run reparam "$OUT/${name}_${n}_reparam" "$ADAPTEX" reparam "$e/mesh.obj" "$e/diffuse.png" --size "$n")
    if [[ $HAVE_SHRINK == 1 ]]; then
      tests+=" $(run shrink "$OUT/${name}_${n}_shrink" "$ADAPTEX" shrink "$e/mesh.obj" --size "$n")"
    fi
    # shellcheck disable=SC2086  # $tests is a list of --test options
    "$EVAL" compare "$e/mesh.obj" "$e/diffuse.png" --size "$n" $tests |
      python3 -c "import json,sys; j=json.load(sys.stdin); j['asset']='$name'; print(json.dumps(j))" >> "$OUT/table.jsonl"
  done
done

python3 - "$OUT/table.jsonl" "$HAVE_SHRINK" <<'PY'
import json, statistics, sys
rows = [json.loads(l) for l in open(sys.argv[1])]
methods = ['reparam'] + (['shrink'] if sys.argv[2] == '1' else [])
def cell(r, m):
    x = r['results'].get(m)
    if x is None:
        return 'failed | | '
    s = '—' if x['saving'] < 0 else f"{x['saving']:.2f}×{'*' if x['saving_extrapolated'] else ''}"
    return f"{x['psnr']:.2f} | {x['gain']:+.2f} | {s}"
head = '| asset | N | downsized | ' + ' | '.join(f'`{m}` | gain | saving' for m in methods) + ' |'
print(head)
print('|' + '---|' * (3 + 3 * len(methods)))
for r in rows:
    print(f"| {r['asset']} | {r['size']} | {r['downsized']:.2f} | " + ' | '.join(cell(r, m) for m in methods) + ' |')
print()
print('| asset | N | faces in | shared in | ' + ' | '.join(f'`{m}` faces | flipped | degenerate | shared' for m in methods) + ' |')
print('|' + '---|' * (4 + 4 * len(methods)))
def geo(r, m):
    x = r['results'].get(m)
    if x is None:
        return ' | | | '
    g = x['geometry']
    return f"{g['faces']} ({100 * g['face_growth']:+.0f} %) | {g['flipped_vs_input']} | {g['degenerate_uv_faces']} | {100 * g['shared_texels']:.0f} %"
for r in rows:
    i = r['input']
    print(f"| {r['asset']} | {r['size']} | {i['faces']} | {100 * i['shared_texels']:.0f} % | " + ' | '.join(geo(r, m) for m in methods) + ' |')
print()
for m in methods:
    for n in sorted({r['size'] for r in rows}, reverse=True):
        g = [r['results'][m]['gain'] for r in rows if r['size'] == n and m in r['results']]
        s = [r['results'][m]['saving'] for r in rows if r['size'] == n and m in r['results'] and r['results'][m]['saving'] > 0]
        failed = sum(1 for r in rows if r['size'] == n and m not in r['results'])
        if g:
            print(f"{m} at {n}²: median gain {statistics.median(g):+.2f} dB, worst {min(g):+.2f} dB, "
                  f"median saving {statistics.median(s) if s else float('nan'):.2f}×, {failed} failed")
PY
