#!/usr/bin/env bash
# ViSP sensor-aided pose estimation. Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
#
# Builds this repository's modules (robust, pose_gravity, laser_conic) as ViSP contrib modules inside
# a minimal ViSP 3.5.0 built from Debian's source package, then runs their tests with ctest there.
#
#   bash scripts/build_as_visp_contrib.sh [--work DIR] [--jobs N] [--no-apt] [--no-tests]
#
#   --work DIR   where the ViSP source and build go (default /tmp/visp-contrib; never the repository)
#   --jobs N     parallel compile jobs (default 2); the build runs under `nice -n 19`
#   --no-apt     do not touch apt (the ViSP source must already be in DIR)
#   --no-tests   build only, run no test
#
# Steps: adds a deb-src entry mirroring the Debian deb entry of apt's sources (deb822 or one-line
# format), `apt-get update`, `apt-get source visp`, installs the build dependencies that are missing,
# configures ViSP with only core, vision, io, robot, visual_features and vs plus our modules
# (-DVISP_CONTRIB_MODULES_PATH=<repo>/modules; no ViSP demos, examples, tutorials or apps), builds our
# three libraries and their test executables only, and runs those tests. Needs root for apt (or sudo).
set -euo pipefail

repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
work=/tmp/visp-contrib
jobs=2
use_apt=1
run_tests=1
while [ $# -gt 0 ]; do
  case "$1" in
    --work) work="$2"; shift 2 ;;
    --jobs) jobs="$2"; shift 2 ;;
    --no-apt) use_apt=0; shift ;;
    --no-tests) run_tests=0; shift ;;
    -h|--help) sed -n '2,20p' "$0"; exit 0 ;;
    *) echo "build_as_visp_contrib.sh: unknown option '$1' (see --help)" >&2; exit 2 ;;
  esac
done
case "$(cd "$(dirname "$work")" 2>/dev/null && pwd)/$(basename "$work")/" in
  "$repo"/*) echo "build_as_visp_contrib.sh: --work must be outside the repository ($repo)" >&2; exit 2 ;;
esac
mkdir -p "$work"
work="$(cd "$work" && pwd)"
log() { echo "[contrib $(date -u +%H:%M:%S)] $*"; }
t_start=$(date +%s)

as_root() {
  if [ "$(id -u)" -eq 0 ]; then "$@"; elif command -v sudo >/dev/null 2>&1; then sudo "$@"; else
    echo "build_as_visp_contrib.sh: '$*' needs root (or sudo)" >&2; exit 1; fi
}

# --- 1. ViSP source from Debian's archive -------------------------------------------------------
has_deb_src() {
  grep -rqsE '^(Types:.*deb-src|deb-src )' /etc/apt/sources.list /etc/apt/sources.list.d/ 2>/dev/null
}

add_deb_src() {
  local deb822=/etc/apt/sources.list.d/debian.sources
  if [ -f "$deb822" ]; then
    # deb822 (Debian 12 default): the same entries with Types: deb-src, in a file of their own.
    log "adding deb-src entries mirroring $deb822"
    sed -E 's/^Types:.*/Types: deb-src/' "$deb822" | as_root tee /etc/apt/sources.list.d/debian-src.sources >/dev/null
  elif grep -qsE '^deb ' /etc/apt/sources.list; then
    log "adding deb-src lines mirroring /etc/apt/sources.list"
    grep -E '^deb ' /etc/apt/sources.list | sed -E 's/^deb /deb-src /' |
      as_root tee /etc/apt/sources.list.d/debian-src.list >/dev/null
  else
    echo "build_as_visp_contrib.sh: no Debian 'deb' entry found in apt's sources to mirror" >&2
    exit 1
  fi
}

src_dir="$(find "$work" -maxdepth 1 -type d -name 'visp-3.5.0*' | head -n 1)"
if [ -z "$src_dir" ]; then
  if [ "$use_apt" -eq 0 ]; then
    echo "build_as_visp_contrib.sh: no ViSP source in $work and --no-apt given" >&2; exit 1
  fi
  has_deb_src || add_deb_src
  log "apt-get update"
  as_root apt-get update -qq
  command -v dpkg-source >/dev/null || as_root apt-get install -y -qq --no-install-recommends dpkg-dev
  log "apt-get source visp into $work"
  (cd "$work" && apt-get source -qq visp 2>&1 | grep -v "unsandboxed" || true)
  src_dir="$(find "$work" -maxdepth 1 -type d -name 'visp-3.5*' | head -n 1)"
  [ -n "$src_dir" ] || { echo "build_as_visp_contrib.sh: apt-get source visp gave no visp-3.5 folder" >&2; exit 1; }
fi
log "ViSP source: $src_dir"

# --- 2. Build dependencies that are missing -----------------------------------------------------
# What the minimal ViSP (core, vision, io, robot, visual_features, vs) and our modules need; the rest of ViSP's build
# dependencies (Debian's debian/control) is not required for these modules.
needed=(build-essential cmake pkg-config libeigen3-dev liblapack-dev libblas-dev libpng-dev libjpeg-dev
        zlib1g-dev libopencv-dev libceres-dev libgtest-dev)
if [ "$use_apt" -eq 1 ]; then
  missing=()
  for p in "${needed[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
  done
  if [ ${#missing[@]} -gt 0 ]; then
    log "installing missing build dependencies: ${missing[*]}"
    as_root env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends "${missing[@]}"
  else
    log "build dependencies already installed"
  fi
fi

# --- 3. Configure a minimal ViSP with our modules -----------------------------------------------
build="$work/build"
# laser_conic needs visual_features (vpFeatureLaserPlane is a vpBasicFeature) and its tests vs (vpServo).
off_modules=(ar blob detection gui imgproc klt mbt me sensor tt tt_mi java_bindings_generator)
module_flags=()
for m in "${off_modules[@]}"; do module_flags+=("-DBUILD_MODULE_visp_$m=OFF"); done
log "configuring ViSP in $build"
t_conf=$(date +%s)
cmake -S "$src_dir" -B "$build" -Wno-dev \
  -DCMAKE_BUILD_TYPE=Release -DBUILD_SHARED_LIBS=ON -DUSE_CXX_STANDARD=17 \
  -DBUILD_TESTS=ON -DBUILD_EXAMPLES=OFF -DBUILD_DEMOS=OFF -DBUILD_TUTORIALS=OFF -DBUILD_APPS=OFF \
  -DBUILD_JAVA=OFF -DBUILD_COVERAGE=OFF -DENABLE_SOLUTION_FOLDERS=OFF \
  "${module_flags[@]}" \
  -DVISP_CONTRIB_MODULES_PATH="$repo/modules" >"$work/configure.log" 2>&1 ||
  { tail -n 40 "$work/configure.log"; echo "build_as_visp_contrib.sh: configure failed, see $work/configure.log" >&2; exit 1; }
grep -E "To be built:|Disabled:|Unavailable:" -A1 "$work/configure.log" | sed 's/^/  /' || true

# --- 4. Build our libraries and their tests (not ViSP's own tests) --------------------------------
targets=(visp_robust visp_pose_gravity visp_laser_conic)
test_names=()
for m in robust pose_gravity laser_conic; do
  for t in "$repo/modules/$m"/test/*.cpp; do
    [ -e "$t" ] || continue
    test_names+=("$m-$(basename "$t" .cpp)") # the executable <module>-<file>, as in the standalone build
  done
done
if [ "$run_tests" -eq 1 ]; then targets+=("${test_names[@]}"); fi
t_build=$(date +%s)
# ViSP's own libraries first, so that a failure in our modules leaves them built for the next run.
visp_targets=(visp_core visp_vision visp_io visp_robot visp_visual_features visp_vs)
log "building ViSP's ${visp_targets[*]} (nice -n 19, -j$jobs)"
nice -n 19 cmake --build "$build" -j "$jobs" --target "${visp_targets[@]}" >"$work/build-visp.log" 2>&1 ||
  { grep -E "error|Error" "$work/build-visp.log" | head -n 40; echo "build_as_visp_contrib.sh: ViSP build failed, see $work/build-visp.log" >&2; exit 1; }
t_visp=$(date +%s)
log "ViSP libraries built in $((t_visp - t_build)) s"
log "building ${targets[*]}"
nice -n 19 cmake --build "$build" -j "$jobs" --target "${targets[@]}" >"$work/build.log" 2>&1 ||
  { grep -E "error|Error" "$work/build.log" | head -n 40; echo "build_as_visp_contrib.sh: build failed, see $work/build.log" >&2; exit 1; }
t_built=$(date +%s)
log "our modules and tests built in $((t_built - t_visp)) s (configure $((t_build - t_conf)) s)"

# --- 5. Run our tests with ctest inside ViSP's build ----------------------------------------------
status=0
if [ "$run_tests" -eq 1 ] && [ ${#test_names[@]} -gt 0 ]; then
  # ctest names each GoogleTest case <module>-<file>.<Suite>.<Case>, as the standalone build does.
  regex="^($(IFS='|'; echo "${test_names[*]}"))\\."
  (cd "$build" && nice -n 19 ctest -R "$regex" --output-on-failure -j "$jobs") || status=$?
fi
log "total $(( $(date +%s) - t_start )) s; ViSP build folder: $build"
exit $status
