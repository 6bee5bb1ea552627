#!/usr/bin/env bash
# Builds (Release) and runs the peer benchmark and the full stress programs; the markdown tables are
# printed and written to $BUILD_DIR/benchmark-results.md (doc/results.md holds them: scripts/update_results.sh --speed).
#   scripts/run_benchmarks.sh [--quick]      (--quick: fewer instances and 1e5 stress configurations)
# Environment: BUILD_DIR (default build-bench), JOBS (default 2), SEED (default 42).
# Each row of the tables is one Google Benchmark run (median over repetitions of the benchmark thread's
# CPU time, benchmark/peers/benchTimer.cpp); bench-peers also takes Google Benchmark's --benchmark_* flags.
# Timings are only comparable on an otherwise idle machine: close other jobs first.
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD_DIR="${BUILD_DIR:-build-bench}"
JOBS="${JOBS:-2}"
SEED="${SEED:-42}"
QUICK="${1:-}"

cmake -S . -B "$BUILD_DIR" -DCMAKE_BUILD_TYPE=Release -DVSP_BUILD_BENCHMARKS=ON >/dev/null
cmake --build "$BUILD_DIR" -j"$JOBS" --target bench-peers stress-gravity stress-laser

out="$BUILD_DIR/benchmark-results.md"
{
  echo "Machine: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //'), $(nproc) cores; $(date -u +%F)"
  "$BUILD_DIR/benchmark/peers/bench-peers" --seed "$SEED" $QUICK
  echo
  echo "### Stress (random exact configurations)"
  echo
  echo '```'
  if [ "$QUICK" = "--quick" ]; then
    "$BUILD_DIR/benchmark/stress/stress-gravity" --solver all --n 1e5
    "$BUILD_DIR/benchmark/stress/stress-laser" --n 1e5
  else
    "$BUILD_DIR/benchmark/stress/stress-gravity" --solver p3p --n 1e7
    "$BUILD_DIR/benchmark/stress/stress-gravity" --solver p2p --n 1e6
    "$BUILD_DIR/benchmark/stress/stress-gravity" --solver ls --n 1e6
    "$BUILD_DIR/benchmark/stress/stress-laser" --n 1e6
  fi
  echo '```'
} | tee "$out"
echo "written: $out"
