#!/usr/bin/env bash
# Installs the dependencies, then runs every check of the project, each as a stage:
#   format      scripts/check_format.sh: the sources as .clang-format says
#   structure   scripts/check_structure.sh: no library function over 80 lines, no library file over 600
#   build+ctest everything built in build/ (or VSP_BUILD_DIR) with the tests on, the whole ctest suite
#   clang-tidy  .clang-tidy on the library sources (modules/*/src), run-clang-tidy -j<cores>; any finding fails
#   doxygen     the HTML reference of the public headers, warnings as errors
#   sanitizers  the libraries and their module tests built with ASan + UBSan (VSP_ENABLE_SANITIZERS) in
#               build-sanitize/ (or VSP_SANITIZE_BUILD_DIR), the module tests run under them (leaks on),
#               the heaviest statistical tests with fewer repetitions (VSP_REDUCED_TRIALS=1)
# Every stage runs even when an earlier one failed; a summary with the time of each stage ends the run,
# and the exit status is non-zero when any stage failed.
# Usage: bash scripts/test.sh [extra cmake options of the main build]   (as root, or with sudo available)
# Skip stages in a quick local run (the default, and CI, runs them all): VSP_SKIP_FORMAT=1,
# VSP_SKIP_STRUCTURE=1, VSP_SKIP_TIDY=1, VSP_SKIP_DOC=1, VSP_SKIP_SANITIZERS=1. Parallel jobs: VSP_JOBS
# (default: the number of cores). A new build folder uses Ninja when it is installed (it keeps both cores
# busy where make waits for one target after another); a folder configured earlier keeps its generator.
# The build folder is always configured with the tests on, whatever an earlier configuration (e.g. of
# another script) left in its cache, and the run fails when ctest finds no test.
# VSP_CONTRIB_BUILD=1 also builds a minimal ViSP with the modules as contrib modules and runs their
# tests there (scripts/build_as_visp_contrib.sh, about 10-25 minutes on 2 cores; off by default).
set -uo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
bash "$here/scripts/install_deps.sh" || exit 1
build="${VSP_BUILD_DIR:-$here/build}"
sanitize_build="${VSP_SANITIZE_BUILD_DIR:-$here/build-sanitize}"
jobs="${VSP_JOBS:-$(nproc)}"
# A compiler cache when the machine has one (scripts/install_deps.sh installs it); nothing depends on it.
launcher=()
if command -v ccache >/dev/null 2>&1; then launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache); fi
# generator DIR: "-G Ninja" for a new build folder when ninja is installed, nothing otherwise.
generator() {
  if [ ! -f "$1/CMakeCache.txt" ] && command -v ninja >/dev/null 2>&1; then echo "-G Ninja"; fi
}

summary=()
failed=0
passed_stages=0
failed_stages=0
# stage NAME COMMAND...: runs the command, records its status and wall time.
stage() {
  local name="$1"; shift
  local start=$SECONDS status=0
  echo
  echo "==== $name"
  "$@" || status=$?
  local verdict="ok"
  if [ "$status" -ne 0 ]; then
    verdict="FAILED (status $status)"; failed=1; failed_stages=$((failed_stages + 1))
  else
    passed_stages=$((passed_stages + 1))
  fi
  summary+=("$(printf '%-12s %-22s %4d s' "$name" "$verdict" $((SECONDS - start)))")
}
skipped() { summary+=("$(printf '%-12s %-22s' "$1" "skipped ($2=1)")"); }

malloc_tunables="glibc.malloc.trim_threshold=4294967295:glibc.malloc.mmap_threshold=33554432"
build_and_ctest() {
  # BUILD_TESTING and the program folders are forced on: the suite tests the examples, the CLIs and the
  # tutorials too; compile_commands.json is for clang-tidy. Extra options come last and may change the rest.
  # shellcheck disable=SC2046 # generator: zero or two words
  cmake -S "$here" -B "$build" $(generator "$build") -DCMAKE_BUILD_TYPE=Release -DBUILD_TESTING=ON \
    -DVSP_BUILD_EXAMPLES=ON -DVSP_BUILD_TUTORIALS=ON -DCMAKE_EXPORT_COMPILE_COMMANDS=ON "${launcher[@]}" "$@" &&
    cmake --build "$build" -j "$jobs" &&
    # --no-tests=error: a build without tests is a failure, never a silent success. glibc's allocator told to
    # keep the memory it frees (trim) and to serve blocks up to 32 MB from its heap (mmap): the tests render
    # and free full frames of 8-23 MB over and over, and each one handed back to the kernel came back as page
    # faults (testLaserConicGuidedSearch: 45.6 s with the defaults, 22.1 s so). Speed only: the same results.
    (cd "$build" && GLIBC_TUNABLES="$malloc_tunables" ctest --output-on-failure --no-tests=error -j "$jobs")
}

clang_tidy() {
  # The libraries only (the programs and tests were checked when they were written; their full run takes
  # about ten times longer): every .cpp of modules/*/src, with the headers they include.
  BUILD_DIR="$build" JOBS="$jobs" bash "$here/scripts/run_clang_tidy.sh" "$here/modules/[a-z_]+/src/.*\.cpp$"
}

doxygen_doc() {
  # The HTML reference of the public headers; doc/Doxyfile.in makes every warning (an undocumented public
  # member, a broken reference) an error.
  cmake --build "$build" --target doc
}

sanitizers() {
  # The libraries and the module tests only (not the programs, tutorials and installed-package tests:
  # they run the same library code on the same data and would double the build). Each test executable is
  # one ctest test (VSP_TESTS_PER_EXECUTABLE): its cases run in one process, as a process started under
  # AddressSanitizer costs about a second (a case per process: 344 s of tests, 274 s this way, and no
  # listing of the cases after each link). -O1 and no debug
  # information: the cheapest build in which the Ceres-based tests stay fast (VSP_ENABLE_SANITIZERS adds
  # -fno-omit-frame-pointer, so the reports' stacks are whole, with function names). For file and line
  # numbers in a report, rebuild the test with -g and run it again, e.g.
  #   cmake -B build-sanitize -DCMAKE_CXX_FLAGS_RELEASE="-O1 -g -DNDEBUG" && cmake --build build-sanitize \
  #     --target <module>-<testFile> && (cd build-sanitize && ctest -R <test> --output-on-failure)
  local modules_regex="^(robust|pose_gravity|laser_conic)-"
  # shellcheck disable=SC2046 # generator: zero or two words
  cmake -S "$here" -B "$sanitize_build" $(generator "$sanitize_build") -DCMAKE_BUILD_TYPE=Release \
    -DCMAKE_CXX_FLAGS_RELEASE="-O1 -DNDEBUG" -DVSP_ENABLE_SANITIZERS=ON \
    -DBUILD_TESTING=ON -DVSP_BUILD_EXAMPLES=OFF -DVSP_BUILD_TUTORIALS=OFF -DVSP_BUILD_BENCHMARKS=OFF \
    -DVSP_TESTS_PER_EXECUTABLE=ON "${launcher[@]}" >/dev/null || return 1
  local targets
  mapfile -t targets < <(for f in "$here"/modules/*/test/*.cpp; do
    echo "$(basename "$(dirname "$(dirname "$f")")")-$(basename "$f" .cpp)"; done)
  cmake --build "$sanitize_build" -j "$jobs" --target "${targets[@]}" || return 1
  # Any sanitizer report fails the test that produced it; leaks are reported too, the suppressions
  # file lists the third-party ones this project cannot fix. VSP_REDUCED_TRIALS=1: the few statistical
  # tests that repeat the same code thousands of times (laser_test::trials, gravity_test::trials) run
  # fewer repetitions here; their full counts run in the build+ctest stage.
  (cd "$sanitize_build" && VSP_REDUCED_TRIALS=1 \
    ASAN_OPTIONS="detect_leaks=1:abort_on_error=1:strict_string_checks=1:check_initialization_order=1" \
    UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1" \
    LSAN_OPTIONS="suppressions=$here/benchmark/sanitizers/lsan.supp:print_suppressions=0" \
    ctest --output-on-failure --no-tests=error -j "$jobs" -R "$modules_regex")
}

if [ "${VSP_SKIP_FORMAT:-0}" = 1 ]; then skipped format VSP_SKIP_FORMAT; else
  stage format bash "$here/scripts/check_format.sh"; fi
if [ "${VSP_SKIP_STRUCTURE:-0}" = 1 ]; then skipped structure VSP_SKIP_STRUCTURE; else
  stage structure bash "$here/scripts/check_structure.sh"; fi
stage build+ctest build_and_ctest "$@"
if [ "${VSP_SKIP_TIDY:-0}" = 1 ]; then skipped clang-tidy VSP_SKIP_TIDY; else stage clang-tidy clang_tidy; fi
if [ "${VSP_SKIP_DOC:-0}" = 1 ]; then skipped doxygen VSP_SKIP_DOC; else stage doxygen doxygen_doc; fi
# The sanitizer stage runs on every submission; its cost (about 7.5 minutes on 2 cores with a cold
# compiler cache: 4.5 to build, 3 to test) is the price of catching memory and undefined-behaviour errors
# before users do. The whole script, cold, in a fresh clone: 20-21 minutes on 2 cores (CHANGELOG.md).
if [ "${VSP_SKIP_SANITIZERS:-0}" = 1 ]; then skipped sanitizers VSP_SKIP_SANITIZERS; else
  stage sanitizers sanitizers; fi
if [ "${VSP_CONTRIB_BUILD:-0}" = 1 ]; then
  stage contrib bash "$here/scripts/build_as_visp_contrib.sh" --work "${VSP_CONTRIB_WORK:-/tmp/visp-contrib}" \
    --jobs "$jobs"
fi

echo
echo "==== summary (scripts/test.sh)"
printf '%s\n' "${summary[@]}"
echo "stages: $passed_stages passed, $failed_stages failed"
if [ "$failed" -ne 0 ]; then
  echo "scripts/test.sh: FAILED (see the stages above)"
  exit 1
fi
echo "scripts/test.sh: all stages passed"
