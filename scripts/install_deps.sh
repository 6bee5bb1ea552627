#!/usr/bin/env bash
# Installs the Debian 12 packages this project builds, tests and benchmarks with.
# Run as root (or through sudo). Safe to run again: apt skips what is already there.
# clang-format, clang-tidy: the format and static-analysis stages of scripts/test.sh; ccache: optional,
# used by scripts/test.sh when present (a second run then recompiles only what changed); ninja-build: the
# generator scripts/test.sh gives its new build folders (it keeps every core busy across targets).
set -euo pipefail

if [ "$(id -u)" -ne 0 ]; then
  if command -v sudo >/dev/null 2>&1; then exec sudo "$0" "$@"; fi
  echo "install_deps.sh: run as root (apt-get needs it)" >&2
  exit 1
fi

export DEBIAN_FRONTEND=noninteractive
apt-get update -qq
apt-get install -y -qq --no-install-recommends \
  build-essential cmake ninja-build pkg-config git \
  libvisp-dev libeigen3-dev libceres-dev libopencv-dev libopengv-dev \
  libgtest-dev libgmock-dev libbenchmark-dev \
  doxygen graphviz clang clang-tidy clang-format ccache >/dev/null
echo "install_deps.sh: dependencies installed"
