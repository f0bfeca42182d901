#!/usr/bin/env bash
# Installs the Debian bookworm packages revisit needs. A no-op when they are all installed.
# Usage: scripts/setup-debian.sh [--fuzz]   (clang and its fuzzer runtime are always installed)
set -euo pipefail

packages=(
  build-essential cmake pkg-config
  libeigen3-dev libtbb-dev robin-map-dev libopencv-dev libceres-dev
  libyaml-cpp-dev nlohmann-json3-dev libcli11-dev zlib1g-dev
  libmrpt-maps-dev libmrpt-opengl-dev libmrpt-img-dev mrpt-common libosmesa6-dev
  libgtest-dev libbenchmark-dev
  chromium
  clang libclang-rt-14-dev ccache
  slurm-wlm munge
)
# slurm-wlm and munge: `revisit batch --engine slurm` and its test, which starts a single-node cluster.
# --fuzz is kept for scripts/fuzz.sh; clang and its fuzzer runtime are part of the normal setup, since
# the test suite's fuzz smoke needs them.

missing=()
for package in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$package")
  fi
done
if [[ ${#missing[@]} -eq 0 ]]; then
  exit 0
fi

sudo=""
if [[ "$(id -u)" -ne 0 ]]; then
  sudo="sudo"
fi
echo "revisit setup: installing ${missing[*]}"
$sudo apt-get update
DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y --no-install-recommends "${missing[@]}"
