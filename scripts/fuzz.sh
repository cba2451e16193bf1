#!/usr/bin/env bash
# Runs one libFuzzer target for SECONDS (default 60): scripts/fuzz.sh TARGET [SECONDS]
# TARGET: obj off ply stl gltf strokes png project (or "all", SECONDS each).
# Builds with clang + -fsanitize=fuzzer,address,undefined into $FUZZ_BUILD_DIR (default build-fuzz-clang);
# installs clang and libclang-rt-14-dev first if missing (scripts/setup.sh --fuzz).
# The corpus grows in $FUZZ_BUILD_DIR/corpus/TARGET (seeded from tests/fuzz/seeds/TARGET); a crash,
# timeout (> 10 s) or out-of-memory (> 2 GB) input is written to $FUZZ_BUILD_DIR/findings/ and the
# script exits non-zero.
set -euo pipefail
cd "$(dirname "$0")/.."
target=${1:?usage: scripts/fuzz.sh TARGET [SECONDS]}
seconds=${2:-60}
build=${FUZZ_BUILD_DIR:-build-fuzz-clang}
all=(obj off ply stl gltf strokes png project)
if [ "$target" = all ]; then
  for t in "${all[@]}"; do "$0" "$t" "$seconds"; done
  exit 0
fi
scripts/setup.sh --fuzz >/dev/null
CC=clang CXX=clang++ cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DADAPTEX_FUZZ=ON \
  -DADAPTEX_BUILD_TESTS=OFF -DADAPTEX_BUILD_BENCH=OFF -DADAPTEX_BUILD_STUDIO=OFF -DADAPTEX_WITH_CGAL=OFF >/dev/null
cmake --build "$build" --target "fuzz_$target" -j "$(nproc)"
corpus="$build/corpus/$target"
mkdir -p "$corpus" "$build/findings"
cp -n tests/fuzz/seeds/"$target"/* "$corpus"/ 2>/dev/null || true
ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
  "$build/tests/fuzz/fuzz_$target" "$corpus" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 \
  -malloc_limit_mb=2048 -max_len=65536 -artifact_prefix="$build/findings/$target-" -print_final_stats=1
