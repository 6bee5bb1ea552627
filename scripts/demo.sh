#!/usr/bin/env bash
# Installs the dependencies, builds the project and runs the main demo on the data shipped in data/.
# Results (CSV, PNG) go to ./demo-output unless VSP_DEMO_OUTPUT says otherwise.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
bash "$here/scripts/install_deps.sh"
build="${VSP_BUILD_DIR:-$here/build}"
cmake -S "$here" -B "$build" -DCMAKE_BUILD_TYPE=Release -DBUILD_TESTING=OFF
cmake --build "$build" -j "$(nproc)"
# The demo creates the output folder itself, after checking that it is not inside data/.
out="${VSP_DEMO_OUTPUT:-$PWD/demo-output}"
"$build/example/demo/vsp-demo" --output "$out"
