#!/usr/bin/env bash
# ctest's `python` test: the module's pytest suite, with the interpreter the module was built for.
# Exits 77 (ctest: skipped) with the reason when pytest is missing.
# Usage: run_pytest.sh PYTHON TESTS_DIR [pytest arguments...]
set -euo pipefail
python=${1:?usage: run_pytest.sh PYTHON TESTS_DIR}
tests=${2:?usage: run_pytest.sh PYTHON TESTS_DIR}
shift 2
if ! "$python" -c "import pytest" 2>/dev/null; then
  echo "skipped: $python has no pytest (scripts/setup-debian.sh --test installs python3-pytest)"
  exit 77
fi
exec "$python" -m pytest -q -p no:cacheprovider "$tests" "$@"
