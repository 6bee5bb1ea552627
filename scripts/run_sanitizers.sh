#!/usr/bin/env bash
# Builds the whole project with AddressSanitizer + UndefinedBehaviorSanitizer (VSP_ENABLE_SANITIZERS)
# and runs the complete ctest suite under them; prints the wall time of each phase.
#   scripts/run_sanitizers.sh [extra ctest arguments, e.g. -L stress or -R laser]
# Environment: BUILD_DIR (default build-asan), JOBS (default 2), BUILD_TYPE (default RelWithDebInfo:
# optimised so that the Ceres-based tests stay fast, with line numbers in the reports), CMAKE_ARGS (extra
# cmake options, e.g. "-DVSP_BUILD_EXAMPLES=OFF -DVSP_BUILD_TUTORIALS=OFF" for the module tests only).
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD_DIR="${BUILD_DIR:-build-asan}"
JOBS="${JOBS:-2}"
BUILD_TYPE="${BUILD_TYPE:-RelWithDebInfo}"
read -r -a EXTRA_CMAKE_ARGS <<<"${CMAKE_ARGS:-}"

# Any sanitizer report fails the test that produced it. Leaks are reported too; the suppressions
# file (benchmark/sanitizers/lsan.supp) lists the third-party ones we cannot fix.
export ASAN_OPTIONS="${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=1:strict_string_checks=1:detect_stack_use_after_return=1:check_initialization_order=1}"
export UBSAN_OPTIONS="${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}"
export LSAN_OPTIONS="${LSAN_OPTIONS:-suppressions=$(pwd)/benchmark/sanitizers/lsan.supp:print_suppressions=0}"

start=$(date +%s)
cmake -S . -B "$BUILD_DIR" -DCMAKE_BUILD_TYPE="$BUILD_TYPE" -DVSP_ENABLE_SANITIZERS=ON "${EXTRA_CMAKE_ARGS[@]}" >/dev/null
cmake --build "$BUILD_DIR" -j"$JOBS"
built=$(date +%s)
status=0
(cd "$BUILD_DIR" && ctest -j"$JOBS" --output-on-failure "$@") || status=$?
done_=$(date +%s)
echo "sanitizers: build $((built - start)) s, ctest $((done_ - built)) s, total $((done_ - start)) s, ctest status $status"
exit $status
