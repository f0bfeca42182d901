#!/usr/bin/env bash
# Runs the test suite through ctest, then lists every skipped test with the reason it gave (ctest alone
# prints skip reasons only with -V), and closes with one summary line.
# Usage: scripts/run-tests.sh BUILD_DIR JOBS [ctest arguments...]
set -uo pipefail
build_dir=${1:?usage: run-tests.sh BUILD_DIR JOBS [ctest args]}
jobs=${2:-2}
shift 2 || true

ctest --test-dir "$build_dir" --output-on-failure -j "$jobs" "$@" | tee "$build_dir/ctest-output.txt"
status=${PIPESTATUS[0]}

log="$build_dir/Testing/Temporary/LastTest.log"
if [[ -f "$log" ]]; then
  # Each test's output sits between "Output:" and "<end of output>"; GoogleTest writes a skip as
  # "FILE:LINE: Skipped", the reason on the following lines, then "[  SKIPPED ] NAME".
  awk '
    /^[0-9]+\/[0-9]+ Test: / { name = $3; next }
    /: Skipped$/ { in_reason = 1; reason = ""; next }
    in_reason && /^\[  SKIPPED \]/ { in_reason = 0; skipped[name] = reason; order[++n] = name; next }
    in_reason { reason = reason (reason == "" ? "" : " ") $0; next }
    END {
      if (n == 0) exit
      printf "\n%d test(s) skipped, with their reasons:\n", n
      for (i = 1; i <= n; ++i) printf "  skipped %s: %s\n", order[i], (skipped[order[i]] == "" ? "(no reason given)" : skipped[order[i]])
    }' "$log"
fi

# One closing line a reader (or CI) can take in at a glance.
summary=$(grep -E "tests passed, [0-9]+ tests failed out of [0-9]+" "$build_dir/ctest-output.txt" | tail -n 1)
if [[ -n "$summary" ]]; then
  total=$(sed -E 's/.* out of ([0-9]+).*/\1/' <<<"$summary")
  failed=$(sed -E 's/.*tests passed, ([0-9]+) tests failed.*/\1/' <<<"$summary")
  skipped=$(grep -cE "\*\*\*Skipped|Not Run" "$build_dir/ctest-output.txt" || true)
  echo
  echo "tests: $((total - failed - skipped)) passed, $failed failed, $skipped skipped"
fi
exit "$status"
