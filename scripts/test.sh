#!/usr/bin/env bash
# Installs the dependencies, builds everything and runs the whole test suite with ctest.
# Usage: bash scripts/test.sh [extra cmake options]   (as root, or with sudo available)
# The build folder (build/, or VSP_BUILD_DIR) is always configured with the tests on, whatever an earlier
# configuration (e.g. of another script) left in its cache, and the run fails when ctest finds no test.
# VSP_CONTRIB_BUILD=1 also builds a minimal ViSP with the modules as contrib modules and runs their
# tests there (scripts/build_as_visp_contrib.sh, about 10-25 minutes on 2 cores; off by default).
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
bash "$here/scripts/install_deps.sh"
build="${VSP_BUILD_DIR:-$here/build}"
# BUILD_TESTING and the program folders are forced on: the suite tests the examples, the CLIs and the
# tutorials too. Extra options come last and may still change the rest.
cmake -S "$here" -B "$build" -DCMAKE_BUILD_TYPE=Release -DBUILD_TESTING=ON \
  -DVSP_BUILD_EXAMPLES=ON -DVSP_BUILD_TUTORIALS=ON "$@"
cmake --build "$build" -j "$(nproc)"
cd "$build"
# --no-tests=error: a build without tests is a failure, never a silent success.
ctest --output-on-failure --no-tests=error -j "$(nproc)"
if [ "${VSP_CONTRIB_BUILD:-0}" = 1 ]; then
  bash "$here/scripts/build_as_visp_contrib.sh" --work "${VSP_CONTRIB_WORK:-/tmp/visp-contrib}" --jobs "$(nproc)"
fi
