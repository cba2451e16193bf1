#!/usr/bin/env bash
# Runs one libFuzzer target for SECONDS (default 60): scripts/fuzz.sh TARGET [SECONDS [LIBFUZZER OPTIONS...]]
# (e.g. scripts/fuzz.sh off 100000 -runs=10000000: stops after 10 M executions).
# TARGET: obj off ply stl gltf strokes png jpeg tga mtl project brush_preset (or "all", SECONDS each).
# scripts/fuzz.sh smoke [SECONDS]: the test command's fuzz smoke (scripts/test.sh): builds every target
# in one go, runs each for SECONDS (default 15) from its seeds only (a fresh corpus, not the one that
# grows in $FUZZ_BUILD_DIR/corpus), prints one line per target, fails on the first finding.
# Builds with clang + -fsanitize=fuzzer,address,undefined into $FUZZ_BUILD_DIR (default build-fuzz-clang);
# installs clang and libclang-rt-14-dev first if missing (scripts/setup.sh --fuzz).
# The corpus grows in $FUZZ_BUILD_DIR/corpus/TARGET (seeded from tests/fuzz/seeds/TARGET); a crash,
# timeout (> 10 s) or out-of-memory (> 2 GB) input is written to $FUZZ_BUILD_DIR/findings/ and the
# script exits non-zero.
set -euo pipefail
cd "$(dirname "$0")/.."
target=${1:?usage: scripts/fuzz.sh TARGET [SECONDS] | scripts/fuzz.sh smoke [SECONDS]}
build=${FUZZ_BUILD_DIR:-build-fuzz-clang}
all=(obj off ply stl gltf strokes png jpeg tga mtl project brush_preset)
# Every target of tests/fuzz/CMakeLists.txt must be in the list (smoke runs the list): a target added
# there and not here fails here, not silently.
for t in $(sed -n 's/^adaptex_fuzz_target(\([a-z0-9_]*\) .*/\1/p' tests/fuzz/CMakeLists.txt); do
  [[ " ${all[*]} " == *" $t "* ]] || { echo "scripts/fuzz.sh: fuzz_$t (tests/fuzz/CMakeLists.txt) is missing from its target list" >&2; exit 1; }
done
if [ "$target" = all ]; then
  for t in "${all[@]}"; do "$0" "$t" "${2:-60}"; done
  exit 0
fi
scripts/setup.sh --fuzz >/dev/null
CC=clang CXX=clang++ cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1 -DNDEBUG" -DADAPTEX_FUZZ=ON \
  -DADAPTEX_BUILD_TESTS=OFF -DADAPTEX_BUILD_BENCH=OFF -DADAPTEX_BUILD_STUDIO=OFF -DADAPTEX_WITH_CGAL=OFF \
  -DCMAKE_UNITY_BUILD=ON -DCMAKE_UNITY_BUILD_BATCH_SIZE=16 >/dev/null
mkdir -p "$build/findings"
# Targets that write each input to a file (fuzz_project; every target with ADAPTEX_FUZZ_VIA_FILE=1) write
# it under TMPDIR: a memory file system when there is one (on ext4 each rewrite of the file waits for
# the disk: 270 executions per second instead of thousands).
if [ -z "${TMPDIR:-}" ] && [ -d /dev/shm ] && [ -w /dev/shm ]; then export TMPDIR=/dev/shm; fi
# run_target TARGET SECONDS CORPUS [EXTRA...]: one libFuzzer run with the documented limits.
# FUZZ_ASAN_OPTIONS adds to ASAN_OPTIONS (the long runs use malloc_context_size=0: no allocation stack
# is recorded per malloc, ~1.2x faster; a finding is re-run from its saved input for the full report).
run_target() {
  ASAN_OPTIONS=detect_leaks=1${FUZZ_ASAN_OPTIONS:+:$FUZZ_ASAN_OPTIONS} UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
    "$build/tests/fuzz/fuzz_$1" "$3" -max_total_time="$2" -timeout=10 -rss_limit_mb=2048 \
    -malloc_limit_mb=2048 -max_len=65536 -artifact_prefix="$build/findings/$1-" -print_final_stats=1 "${@:4}"
}
if [ "$target" = smoke ]; then
  seconds=${2:-15}
  start=$(date +%s)
  cmake --build "$build" --target "${all[@]/#/fuzz_}" -j "$(nproc)"
  echo "fuzz smoke: built ${#all[@]} targets in $(( $(date +%s) - start )) s"
  for t in "${all[@]}"; do
    corpus=$(mktemp -d)
    cp tests/fuzz/seeds/"$t"/* "$corpus"/
    log="$build/smoke-$t.log"
    if ! run_target "$t" "$seconds" "$corpus" >"$log" 2>&1; then
      rm -rf "$corpus"
      tail -n 40 "$log"
      echo "fuzz smoke: fuzz_$t FAILED (finding in $build/findings/, log $log)"
      exit 1
    fi
    rm -rf "$corpus"
    echo "fuzz smoke: fuzz_$t: $(grep -o 'stat::number_of_executed_units: *[0-9]*' "$log" | grep -o '[0-9]*$') executions in ${seconds} s, $(grep -o 'cov: [0-9]*' "$log" | tail -n 1), 0 findings"
  done
  echo "fuzz smoke: all ${#all[@]} targets clean, $(( $(date +%s) - start )) s in all"
  exit 0
fi
seconds=${2:-60}
cmake --build "$build" --target "fuzz_$target" -j "$(nproc)"
corpus="$build/corpus/$target"
mkdir -p "$corpus"
cp -n tests/fuzz/seeds/"$target"/* "$corpus"/ 2>/dev/null || true
run_target "$target" "$seconds" "$corpus" "${@:3}"
