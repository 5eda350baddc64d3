#!/usr/bin/env bash
# The ctest entry of the Python tool tests: pytest on the folder given (tests/crosscheck,
# tests/nff, ...) in the project's .venv (made by tools/bootstrap --python, which tools/test
# runs). Without .venv it reports a skip (77).
# Usage: tests/run_pytest.sh FOLDER [pytest arguments]
root="$(cd "$(dirname "$0")/.." && pwd)"
if [ ! -x "$root/.venv/bin/python" ]; then
  echo "SKIPPED: no $root/.venv: run tools/bootstrap --python to make it (Mitsuba 3, NumPy, FLIP, pytest)"
  exit 77
fi
folder="$1"
shift
exec "$root/.venv/bin/python" -m pytest -q -p no:cacheprovider "$folder" "$@"
