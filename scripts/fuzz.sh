#!/usr/bin/env bash
# libFuzzer on every reader (clang, ASan, UBSan that halts), one target after another.
# Usage: scripts/fuzz.sh [SECONDS]   each target SECONDS long (default 60); findings in build-fuzz/crashes/
#        scripts/fuzz.sh --smoke     about 60 s over all targets (the `fuzz_smoke` test); exits 77 (skipped)
#                                    when clang or its fuzzer runtime is missing
# FUZZ_KEEP_GOING=1 (long runs): libFuzzer's fork mode goes on after a finding and counts crashes,
# timeouts and OOMs (the log's last "#N ... oom/timeout/crash" line) instead of stopping at the first.
# Every run: -timeout=10 (a hang is a finding), -rss_limit_mb=2048 and -malloc_limit_mb=2048 (memory
# beyond what a small input can justify is a finding). Seeds come from the project's own writers.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
build="${REVISIT_FUZZ_BUILD:-$root/build-fuzz}"
targets=(fuzz_scans fuzz_trajectories fuzz_rawlog fuzz_mcap fuzz_db3 fuzz_ros1 fuzz_carmen fuzz_database fuzz_map_points fuzz_config fuzz_run_folder fuzz_profile)

smoke=0
if [[ "${1:-}" == "--smoke" ]]; then
  smoke=1
  seconds=$((60 / ${#targets[@]}))
  if ! command -v clang++ > /dev/null || ! compgen -G "/usr/lib/llvm-*/lib/clang/*/lib/linux/libclang_rt.fuzzer-x86_64.a" > /dev/null; then
    echo "fuzz smoke skipped: clang and libclang-rt-*-dev are not installed (scripts/setup-debian.sh installs them)"
    exit 77
  fi
else
  seconds="${1:-60}"
  "$root/scripts/setup-debian.sh" --fuzz
fi

mkdir -p "$build"
launcher=()
if command -v ccache > /dev/null; then launcher=(-DCMAKE_C_COMPILER_LAUNCHER=ccache -DCMAKE_CXX_COMPILER_LAUNCHER=ccache); fi
CC=clang CXX=clang++ cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DREVISIT_FUZZ=ON \
  "${launcher[@]}" > "$build/configure.log"
cmake --build "$build" --target fuzz_targets -j "${JOBS:-$(nproc)}" > "$build/build.log" || {
  tail -n 40 "$build/build.log"
  exit 1
}

corpus="$build/corpus"
rm -rf "$build/seeds"
"$build/tests/fuzz_seeds" "$build/seeds"
mkdir -p "$build/crashes"
status=0
keep_going=()
if [[ "${FUZZ_KEEP_GOING:-0}" == 1 ]]; then keep_going=(-fork=1 -ignore_crashes=1 -ignore_ooms=1 -ignore_timeouts=1); fi
for target in "${targets[@]}"; do
  mkdir -p "$corpus/$target" "$build/seeds/$target"
  log="$build/$target.log"
  echo "== $target: ${seconds} s"
  # UBSan and ASan stop at the first report; libFuzzer saves the input in crashes/.
  if ! UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1 ASAN_OPTIONS=detect_leaks=0 \
      "$build/tests/$target" "$corpus/$target" "$build/seeds/$target" -max_total_time="$seconds" \
      -timeout=10 -rss_limit_mb=2048 -malloc_limit_mb=2048 -max_len=16384 -print_final_stats=1 \
      -artifact_prefix="$build/crashes/$target-" "${keep_going[@]}" > "$log" 2>&1; then
    echo "$target: FINDING (see $log and $build/crashes/)"
    grep -E "ERROR|runtime error|SUMMARY|Test unit written" "$log" | head -n 8 || true
    status=1
  fi
  grep -E "stat::number_of_executed_units|stat::average_exec_per_sec|stat::peak_rss_mb" "$log" | tr '\n' ' ' || true
  grep -E "oom/timeout/crash" "$log" | tail -n 1 || true
  echo
done
exit $status
