#!/usr/bin/env bash
# Fetch the real textured assets of docs/assets.md into ASSETS (default /work/assets, outside the
# repository: never commit them) and lay out each as ASSETS/NAME/eval/{mesh.obj,diffuse.png[,normal.png]}
# (triangles with vt, mtllib mesh.mtl naming the maps; the diffuse at 1024² or its native size when smaller), which
# bench/shrink/asset_table.sh reads.
#
#   bench/shrink/get_assets.sh [ASSETS]            # download with git (needs network), then lay out
#   SRC=DIR bench/shrink/get_assets.sh [ASSETS]    # DIR holds the three repositories already checked out
#                                                  # (DIR/tinyrenderer, DIR/common-3d-test-models, DIR/trimesh,
#                                                  #  DIR/glTF-Sample-Assets); no network used
#
# Needs git, python3 and ImageMagick's `convert`. Larger textures are box-filtered to 1024² (an exact
# 2×2 average for 2048²): that 1024² image is the "original" every figure is measured against.
set -euo pipefail
ASSETS=${1:-/work/assets}
HERE=$(cd "$(dirname "$0")" && pwd)
mkdir -p "$ASSETS"

# Sources: repository, commit the figures were made with, path inside it.
TINYRENDERER=https://github.com/ssloy/tinyrenderer            # @87bc715 obj/{african_head,diablo3_pose,boggie}
COMMON3D=https://github.com/alecjacobson/common-3d-test-models # @HEAD data/spot.obj
SPOTTEX=https://www.cs.cmu.edu/~kmcrane/Projects/ModelRepository/spot.zip  # spot_texture.png (Keenan Crane, CC0)
TRIMESH=https://github.com/mikedh/trimesh                      # models/{fuze.obj,fuze.obj.mtl,"fuze uv.jpg",Duck.glb,CesiumMilkTruck.glb}
GLTFASSETS=https://github.com/KhronosGroup/glTF-Sample-Assets  # Models/DamagedHelmet/glTF-Binary/DamagedHelmet.glb

if [[ -z "${SRC:-}" ]]; then
  SRC=$ASSETS/_src
  mkdir -p "$SRC"
  clone() { [[ -d "$SRC/$2" ]] || git clone --depth 1 --filter=blob:none --sparse "$1" "$SRC/$2" && git -C "$SRC/$2" sparse-checkout set "${@:3}"; }
  if ! clone "$TINYRENDERER" tinyrenderer obj/african_head obj/diablo3_pose obj/boggie ||
     ! clone "$COMMON3D" common-3d-test-models data ||
     ! clone "$TRIMESH" trimesh models ||
     ! clone "$GLTFASSETS" glTF-Sample-Assets Models/DamagedHelmet/glTF-Binary; then
    echo "get_assets.sh: cannot download (no network?). Check out these by hand into one folder and rerun with SRC=that folder:" >&2
    printf '  %s\n' "$TINYRENDERER" "$COMMON3D" "$TRIMESH" "$GLTFASSETS" "$SPOTTEX (unzip spot_texture.png into common-3d-test-models/data/)" >&2
    exit 1
  fi
  [[ -f "$SRC/common-3d-test-models/data/spot_texture.png" ]] ||
    echo "get_assets.sh: spot_texture.png is not in $COMMON3D; get it from $SPOTTEX into $SRC/common-3d-test-models/data/" >&2
fi

first() { for f in "$@"; do [[ -f "$f" ]] && { echo "$f"; return; }; done; echo "get_assets.sh: none of: $*" >&2; return 1; }
# [FLIP=-flip] lay NAME OBJ DIFFUSE [NORMAL]: copy the mesh, convert the maps to PNG at min(native, 1024)².
# tinyrenderer's OBJs count v from the top of its TGAs as an image viewer shows them (its renderer
# reads them that way): FLIP=-flip turns the pictures so that v = 0 is their bottom row, as OBJ means.
lay() {
  local name=$1 obj=$2 dif=$3 nrm=${4:-} flip=${FLIP:-}
  local out=$ASSETS/$name/eval
  mkdir -p "$out"
  { echo "mtllib mesh.mtl"; echo "usemtl asset"; grep -v -E '^(mtllib|usemtl) ' "$obj"; } > "$out/mesh.obj"
  convert "$dif" $flip -alpha off -filter box -resize '1024x1024>' "PNG24:$out/diffuse.png"
  printf 'newmtl asset\nKd 1 1 1\nmap_Kd diffuse.png\n' > "$out/mesh.mtl"
  if [[ -n "$nrm" ]]; then
    convert "$nrm" $flip -alpha off -filter box -resize '1024x1024>' "PNG24:$out/normal.png"
    echo "norm normal.png" >> "$out/mesh.mtl"
  fi
  echo "$name: $(grep -c '^f ' "$out/mesh.obj") faces, diffuse $(identify -format '%wx%h' "$out/diffuse.png") from $(basename "$dif")"
}
glb() {  # glb NAME GLB: extract the first baseColor material group, then lay it out
  local name=$1 tmp=$ASSETS/$1/extracted
  python3 "$HERE/glb_extract.py" "$2" "$tmp" >/dev/null
  local dif nrm
  dif=$tmp/$(awk '/baseColor/{print $1; exit}' "$tmp/materials.txt")
  nrm=$(awk '/normal/{print $1; exit}' "$tmp/materials.txt")
  lay "$name" "$tmp/mesh.obj" "$dif" "${nrm:+$tmp/$nrm}"
}

T=$SRC/tinyrenderer/obj
FLIP=-flip lay african_head "$T/african_head/african_head.obj" "$T/african_head/african_head_diffuse.tga" "$T/african_head/african_head_nm_tangent.tga"
FLIP=-flip lay diablo3_pose "$T/diablo3_pose/diablo3_pose.obj" "$T/diablo3_pose/diablo3_pose_diffuse.tga" "$T/diablo3_pose/diablo3_pose_nm_tangent.tga"
FLIP=-flip lay boggie_head "$T/boggie/head.obj" "$T/boggie/head_diffuse.tga" "$T/boggie/head_nm_tangent.tga"
lay spot "$SRC/common-3d-test-models/data/spot.obj" "$(first "$SRC/common-3d-test-models/data/spot_texture.png" "$ASSETS/spot/spot_texture.png")"
lay fuze "$SRC/trimesh/models/fuze.obj" "$SRC/trimesh/models/fuze uv.jpg"
glb duck "$SRC/trimesh/models/Duck.glb"
glb milk_truck "$SRC/trimesh/models/CesiumMilkTruck.glb"
glb damaged_helmet "$(first "$SRC/glTF-Sample-Assets/Models/DamagedHelmet/glTF-Binary/DamagedHelmet.glb" "$ASSETS/damaged_helmet/DamagedHelmet.glb")"
