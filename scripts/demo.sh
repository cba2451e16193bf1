#!/usr/bin/env bash
# Quick start, command 1: set up, build, and run the demo on the embedded default mesh.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
scripts/build.sh
build/apps/cli/adaptex demo -o demo-output
