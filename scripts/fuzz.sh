#!/usr/bin/env bash
# Builds the reader fuzz target with clang (libFuzzer + ASan + UBSan) and runs it.
# Usage: scripts/fuzz.sh [SECONDS]   (default 60). Crashes are saved in build-fuzz/crashes/.
set -euo pipefail
seconds="${1:-60}"
root="$(cd "$(dirname "$0")/.." && pwd)"
build="$root/build-fuzz"
"$root/scripts/setup-debian.sh" --fuzz
CC=clang CXX=clang++ cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DREVISIT_FUZZ=ON
cmake --build "$build" --target fuzz_readers -j "$(nproc)"

# Seed corpus: one small valid file per format, prefixed by the byte that selects its reader.
corpus="$build/corpus"
mkdir -p "$corpus" "$build/crashes"
seed() { { printf "\\x$(printf %02x "$1")"; cat; } > "$corpus/seed-$1"; }
printf '\x00\x00\x80\x3f\x00\x00\x00\x40\x00\x00\x40\x40\x00\x00\x00\x3f' | seed 0
printf 'VERSION 0.7\nFIELDS x y z intensity\nSIZE 4 4 4 4\nTYPE F F F F\nCOUNT 1 1 1 1\nWIDTH 2\nHEIGHT 1\nPOINTS 2\nDATA ascii\n1 2 3 0.5\n4 5 6 1\n' | seed 1
printf 'ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\nproperty float y\nproperty float z\nend_header\n1 2 3\n4 5 6\n' | seed 2
head -c 4096 "/usr/share/mrpt/datasets/localization_demo.rawlog" | seed 3
printf '1 0 0 0 0 1 0 0 0 0 1 0\n1 0 0 1.5 0 1 0 0 0 0 1 0\n' | seed 4

"$build/tests/fuzz_readers" "$corpus" -max_total_time="$seconds" -max_len=8192 -rss_limit_mb=4096 \
  -artifact_prefix="$build/crashes/"
