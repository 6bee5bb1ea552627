#!/usr/bin/env bash
# Installs the dependencies, builds the demo programs and runs the main demo on the data shipped in data/,
# then the quick-start program and the reproduction of Table I of the gravity paper.
# Results (CSV, PNG) go to ./demo-output unless VSP_DEMO_OUTPUT says otherwise.
# Only the demo programs and the command-line programs of doc/usage_cli.md are built, and the configuration of the build folder is left as it is (tests
# included): scripts/test.sh can run before or after this script in the same clone.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
bash "$here/scripts/install_deps.sh"
build="${VSP_BUILD_DIR:-$here/build}"
cmake -S "$here" -B "$build" -DCMAKE_BUILD_TYPE=Release
cmake --build "$build" -j "$(nproc)" --target vsp-demo quickstart table1-gravity-p3p vsp-laser-altimeter \
  vsp-gravity-pose vsp-compare-poses vsp-laser-calibrate vsp-make-laser-calibration-images
# The demo finds data/ from its own location; it creates the output folder itself, after checking
# that it is not inside data/.
out="${VSP_DEMO_OUTPUT:-$PWD/demo-output}"
"$build/example/demo/vsp-demo" --output "$out"
# The quick-start snippets of the README, then the paper's Table I (gravity-aided P3P, 8000 trials).
echo
echo "== Quick start (example/quickstart) =="
"$build/example/quickstart/quickstart"
echo
echo "== Table I of D'Alfonso et al. (example/pose_gravity/table1-gravity-p3p --trials 8000 --seed 1) =="
"$build/example/pose_gravity/table1-gravity-p3p" --trials 8000 --seed 1
# A laser calibration session (12 rendered chessboard views), the input of the calibration commands of
# doc/usage_cli.md: $out/laser_calibration/{camera.xml,laser_true.yaml,images/}.
echo
echo "== Laser calibration images for vsp-laser-calibrate (doc/usage_cli.md) =="
"$build/example/cli/vsp-make-laser-calibration-images" --output "$out/laser_calibration"
