#!/usr/bin/env bash
# Builds the libFuzzer targets with clang (ASan + UBSan) and fuzzes each for FUZZ_SECONDS.
#   scripts/run_fuzz.sh [seconds]        (default 60 per target)
# Environment: BUILD_DIR (default build-bench-fuzz), CXX (default clang++-14 or clang++), JOBS (default 2),
# FUZZ_ARGS (extra libFuzzer options; default -len_control=10 so that inputs long enough for tens of
# points are tried within a one-minute run, instead of a few short ones).
# Corpora are kept in $BUILD_DIR/corpus/<target>, crashing inputs in $BUILD_DIR/artifacts/<target>/.
# Replay a crash with: $BUILD_DIR/benchmark/fuzz/fuzz-<target> <artifact file>
set -euo pipefail
cd "$(dirname "$0")/.."
SECONDS_PER_TARGET="${1:-${FUZZ_SECONDS:-60}}"
BUILD_DIR="${BUILD_DIR:-build-bench-fuzz}"
JOBS="${JOBS:-2}"
CXX_BIN="${CXX:-$(command -v clang++-14 || command -v clang++)}"
read -r -a EXTRA_FUZZ_ARGS <<<"${FUZZ_ARGS:--len_control=10}"
SAN_FLAGS="-fsanitize=fuzzer-no-link,address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer -g"

cmake -S . -B "$BUILD_DIR" -DCMAKE_CXX_COMPILER="$CXX_BIN" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DBUILD_SHARED_LIBS=OFF -DBUILD_TESTING=OFF -DVSP_BUILD_EXAMPLES=OFF -DVSP_BUILD_TUTORIALS=OFF \
  -DVSP_BUILD_FUZZERS=ON -DCMAKE_CXX_FLAGS="$SAN_FLAGS" \
  -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=address,undefined" >/dev/null
cmake --build "$BUILD_DIR" -j"$JOBS" --target fuzz-pose-gravity fuzz-laser-conic fuzz-laser-detector fuzz-laser-filter \
  fuzz-laser-selfcal

status=0
for target in pose-gravity laser-conic laser-detector laser-filter laser-selfcal; do
  corpus="$BUILD_DIR/corpus/$target"
  artifacts="$BUILD_DIR/artifacts/$target/"
  mkdir -p "$corpus" "$artifacts"
  echo "== fuzz-$target for ${SECONDS_PER_TARGET} s"
  # -timeout: one input running longer than 10 s is a hang; -rss_limit_mb: no unbounded memory.
  if ! UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 ASAN_OPTIONS=detect_leaks=1 \
      "$BUILD_DIR/benchmark/fuzz/fuzz-$target" "$corpus" -max_total_time="$SECONDS_PER_TARGET" \
      -timeout=10 -rss_limit_mb=2048 -max_len=8192 -print_final_stats=1 -artifact_prefix="$artifacts" "${EXTRA_FUZZ_ARGS[@]}" \
      2>"$BUILD_DIR/fuzz-$target.log"; then
    echo "fuzz-$target FAILED: see $BUILD_DIR/fuzz-$target.log and $artifacts"
    status=1
  fi
  grep -E "stat::number_of_executed_units|stat::peak_rss_mb|cov:" "$BUILD_DIR/fuzz-$target.log" | tail -3 || true
  echo "corpus: $(ls "$corpus" | wc -l) inputs"
done
exit $status
