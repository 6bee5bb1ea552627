#!/usr/bin/env bash
# Installs the dependencies, builds everything and runs the whole test suite with ctest.
# Usage: bash scripts/test.sh [extra cmake options]   (as root, or with sudo available)
# VSP_CONTRIB_BUILD=1 also builds a minimal ViSP with the modules as contrib modules and runs their
# tests there (scripts/build_as_visp_contrib.sh, about 10-25 minutes on 2 cores; off by default).
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
bash "$here/scripts/install_deps.sh"
build="${VSP_BUILD_DIR:-$here/build}"
cmake -S "$here" -B "$build" -DCMAKE_BUILD_TYPE=Release "$@"
cmake --build "$build" -j "$(nproc)"
cd "$build"
ctest --output-on-failure -j "$(nproc)"
if [ "${VSP_CONTRIB_BUILD:-0}" = 1 ]; then
  bash "$here/scripts/build_as_visp_contrib.sh" --work "${VSP_CONTRIB_WORK:-/tmp/visp-contrib}" --jobs "$(nproc)"
fi
