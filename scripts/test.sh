#!/usr/bin/env bash
# Quick start, command 2: set up, build with warnings as errors, and run the whole test suite.
# Under CI (CI=true) or with --sanitize the suite runs once more under AddressSanitizer + UBSan.
# Then, when clang is there, every libFuzzer target runs for a 15 s smoke (scripts/fuzz.sh smoke).
set -euo pipefail
cd "$(dirname "$0")/.."
sanitize=0
if [ "${CI:-}" = "true" ] || [ "${1:-}" = "--sanitize" ]; then sanitize=1; fi
scripts/setup.sh
jobs=$(nproc)
# Under CI the Release build is a unity build too (16 sources per compiler run, about half the
# compile CPU; docs/reliability.md, "CI time"); locally it stays one source per run, for
# incremental builds and for -Werror on each source alone.
unity=OFF
if [ "$sanitize" = 1 ]; then unity=ON; fi
BUILD_DIR=build scripts/build.sh -DADAPTEX_WERROR=ON -DCMAKE_UNITY_BUILD=$unity -DCMAKE_UNITY_BUILD_BATCH_SIZE=16
echo "== built in ${SECONDS} s =="
( cd build && ctest --output-on-failure -j "$jobs" )
echo "== tests done at ${SECONDS} s =="
if [ "$sanitize" = 1 ]; then
  echo "== again under AddressSanitizer + UndefinedBehaviorSanitizer =="
  # -O1 -g1 (line tables only): ASan's recommended level, half the compile time of -O2 -g, and
  # stack traces still name files and lines. Warnings are errors in the build above; here they are
  # only printed, as GCC 12's flow warnings change with the instrumentation (a -Wmaybe-uninitialized
  # inside <regex> that no other build shows).
  # A unity build (16 sources per compiler run): about half the compile CPU of this pass.
  BUILD_DIR=build-asan scripts/build.sh -DADAPTEX_WERROR=OFF -DADAPTEX_SANITIZE=ON \
    -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1 -DNDEBUG" \
    -DADAPTEX_BUILD_BENCH=OFF -DCMAKE_UNITY_BUILD=ON -DCMAKE_UNITY_BUILD_BATCH_SIZE=16
  ( cd build-asan && ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 \
      ctest --output-on-failure -j "$jobs" -LE no_sanitize )
  echo "== sanitizer pass done at ${SECONDS} s =="
fi
# Fuzz smoke (issue 11, docs/reliability.md): every libFuzzer target for 15 s from its seeds, when
# clang and its libFuzzer runtime are there. Under CI (or --sanitize) they are installed first
# (scripts/setup.sh --fuzz: apt-get only). ADAPTEX_FUZZ_SMOKE=0 skips it.
if [ "$sanitize" = 1 ] && [ "${ADAPTEX_FUZZ_SMOKE:-1}" != 0 ]; then
  scripts/setup.sh --fuzz || echo "setup: clang / libclang-rt-14-dev could not be installed"
fi
if [ "${ADAPTEX_FUZZ_SMOKE:-1}" != 0 ] && command -v clang++ >/dev/null &&
   [ -f "$(clang++ -print-file-name=libclang_rt.fuzzer-x86_64.a)" ]; then
  echo "== fuzz smoke: every libFuzzer target for 15 s (scripts/fuzz.sh smoke) =="
  scripts/fuzz.sh smoke 15
else
  echo "== fuzz smoke skipped: clang / libclang-rt-14-dev not installed (scripts/setup.sh --fuzz) =="
fi
