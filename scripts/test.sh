#!/usr/bin/env bash
# Quick start, command 2: set up, build with warnings as errors, and run the whole test suite.
# Under CI (CI=true) or with --sanitize the suite runs once more under AddressSanitizer + UBSan.
set -euo pipefail
cd "$(dirname "$0")/.."
sanitize=0
if [ "${CI:-}" = "true" ] || [ "${1:-}" = "--sanitize" ]; then sanitize=1; fi
scripts/setup.sh
jobs=$(nproc)
BUILD_DIR=build scripts/build.sh -DADAPTEX_WERROR=ON
( cd build && ctest --output-on-failure -j "$jobs" )
if [ "$sanitize" = 1 ]; then
  echo "== again under AddressSanitizer + UndefinedBehaviorSanitizer =="
  BUILD_DIR=build-asan scripts/build.sh -DADAPTEX_WERROR=ON -DADAPTEX_SANITIZE=ON \
    -DCMAKE_BUILD_TYPE=RelWithDebInfo -DADAPTEX_BUILD_BENCH=OFF
  ( cd build-asan && ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 \
      ctest --output-on-failure -j "$jobs" -LE no_sanitize )
fi
