#!/usr/bin/env bash
# Installs the Debian 12 packages adaptex needs (only the missing ones; sudo only when not root).
set -euo pipefail
PACKAGES=(
  build-essential cmake ninja-build pkg-config ccache git
  libeigen3-dev libsuitesparse-dev libtbb-dev libfftw3-dev
  libassimp-dev libtinyobjloader-dev libtinygltf-dev libstb-dev nlohmann-json3-dev libcli11-dev
  libembree-dev libcgal-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  libglfw3-dev libimgui-dev libgl-dev libgl1-mesa-dri mesa-utils libgtk-3-dev libxi-dev
  xvfb xdotool x11-utils libx11-dev
  python3-dev python3-pybind11 python3-numpy python3-pytest python3-matplotlib python3-venv python3-pip python3-build blender
)
# --fuzz: also what scripts/fuzz.sh needs (clang and its libFuzzer / sanitizer runtimes); not by default.
if [ "${1:-}" = "--fuzz" ]; then PACKAGES+=(clang libclang-rt-14-dev); fi
missing=()
for p in "${PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "setup: all ${#PACKAGES[@]} packages present"
else
  SUDO=""
  if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
  echo "setup: installing ${missing[*]}"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi
# The Khronos glTF Validator (npm gltf-validator) for the export tests, outside the tree and the build:
# tests/paint/gltf_validate.py finds it here and skips with a message where it is absent.
NPM_DIR=${ADAPTEX_NPM_DIR:-${XDG_CACHE_HOME:-$HOME/.cache}/adaptex/npm}
if [ ! -f "$NPM_DIR/node_modules/gltf-validator/package.json" ] && command -v npm >/dev/null; then
  if npm install --prefix "$NPM_DIR" --no-audit --no-fund --silent gltf-validator@2.0.0-dev.3.10 >/dev/null 2>&1; then
    echo "setup: gltf-validator installed in $NPM_DIR"
  else
    echo "setup: could not install the npm package gltf-validator (no registry?); its test will be skipped"
  fi
fi
