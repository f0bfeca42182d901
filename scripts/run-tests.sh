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
grep -E '\*\*\*Skipped' "$build_dir/ctest-output.txt" | sed -E 's/.*Test +#[0-9]+: ([^ ]+) .*/\1/' > "$build_dir/skipped-tests.txt" || true
if [[ -f "$log" ]]; then
  # ctest names the skipped tests ("N/M Test #K: NAME ....***Skipped"); their output in LastTest.log
  # gives the reason: GoogleTest writes "FILE:LINE: Skipped" then the reason up to "[  SKIPPED ]";
  # other tests (SKIP_RETURN_CODE) print it as their last line.
  awk '
    FNR == NR { wanted[$1] = 1; next }
    /^[0-9]+\/[0-9]+ Test: / { name = $3; in_output = 0; in_reason = 0; reason = ""; last_line = ""; next }
    /^Output:$/ { in_output = 1; next }
    /^<end of output>$/ {
      in_output = 0
      if (name in wanted) { order[++n] = name; why[name] = (reason != "" ? reason : last_line) }
      next
    }
    !in_output { next }
    /: Skipped$/ { in_reason = 1; next }
    in_reason && /^\[  SKIPPED \]/ { in_reason = 0; next }
    in_reason { reason = reason (reason == "" ? "" : " ") $0; next }
    NF > 0 && !/^-+$/ { last_line = $0 }
    END {
      if (n == 0) exit
      printf "\n%d test(s) skipped, with their reasons:\n", n
      for (i = 1; i <= n; ++i) printf "  skipped %s: %s\n", order[i], (why[order[i]] == "" ? "(no reason given)" : why[order[i]])
    }' "$build_dir/skipped-tests.txt" "$log"
fi

# One closing line a reader (or CI) can take in at a glance.
summary=$(grep -E "tests passed, [0-9]+ tests failed out of [0-9]+" "$build_dir/ctest-output.txt" | tail -n 1)
if [[ -n "$summary" ]]; then
  total=$(sed -E 's/.* out of ([0-9]+).*/\1/' <<<"$summary")
  failed=$(sed -E 's/.*tests passed, ([0-9]+) tests failed.*/\1/' <<<"$summary")
  skipped=$(wc -l < "$build_dir/skipped-tests.txt")
  echo
  echo "tests: $((total - failed - skipped)) passed, $failed failed, $skipped skipped"
fi
exit "$status"
