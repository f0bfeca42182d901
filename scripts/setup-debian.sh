#!/usr/bin/env bash
# Installs the Debian bookworm packages revisit needs. A no-op when they are all installed.
# Usage: scripts/setup-debian.sh          what building and running `revisit` needs (`make build`, `make demo`)
#        scripts/setup-debian.sh --test   also what the test suite, the fuzz smoke and `make bench` need
#        scripts/setup-debian.sh --fuzz   the same as --test (kept for scripts/fuzz.sh)
set -euo pipefail

# Building and running revisit.
packages=(
  build-essential cmake pkg-config
  libeigen3-dev libtbb-dev robin-map-dev libnanoflann-dev libopencv-dev libceres-dev
  libyaml-cpp-dev nlohmann-json3-dev libcli11-dev zlib1g-dev libbz2-dev libpng-dev
  libmrpt-maps-dev libmrpt-opengl-dev libmrpt-img-dev mrpt-common libosmesa6-dev
  # ROS bags: MCAP chunks, rosbag2 sqlite3, ROS 1 bags through Debian's rosbag_storage (+ the message
  # packages whose types the bags carry)
  libzstd-dev liblz4-dev libsqlite3-dev librosbag-storage-dev librcpputils-dev librcutils-dev
  libsensor-msgs-dev libnav-msgs-dev libgeometry-msgs-dev libtf2-msgs-dev
  # the Python module (python/)
  pybind11-dev python3-dev python3-numpy
)
case "${1:-}" in
  "") ;;
  --test | --fuzz)
    packages+=(
      libgtest-dev libbenchmark-dev ccache
      # the fuzz smoke (libFuzzer needs clang and its runtime)
      clang libclang-rt-14-dev
      # `revisit batch --engine slurm` and its test, which starts a single-node cluster
      slurm-wlm munge
      # the report's page tests render the pages in headless Chromium
      chromium
      # the Python module's tests
      python3-pytest
    )
    ;;
  *)
    echo "usage: scripts/setup-debian.sh [--test]" >&2
    exit 2
    ;;
esac

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
