#!/usr/bin/env python3
"""Golden diagnostics: `tracer --check CASE.scn`, run in the case's folder, must print exactly
CASE.expected on stderr (its first line is the expected exit code, "exit N").

    run_golden.py --tracer build/release/tracer tests/diagnostics/*.scn
    run_golden.py --tracer build/release/tracer --update tests/diagnostics/*.scn   # rewrite
"""

import argparse
import difflib
import pathlib
import subprocess
import sys


def actual_output(tracer: str, case: pathlib.Path) -> str:
    proc = subprocess.run([tracer, "--check", case.name], cwd=case.parent, capture_output=True, text=True, timeout=60)
    # Absolute paths differ between checkouts.
    stderr = proc.stderr.replace(str(case.parent.resolve()), "<dir>")
    return f"exit {proc.returncode}\n{stderr}"


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--tracer", required=True)
    parser.add_argument("--update", action="store_true", help="rewrite the .expected files")
    parser.add_argument("cases", nargs="+", type=pathlib.Path)
    args = parser.parse_args()
    args.tracer = str(pathlib.Path(args.tracer).resolve())
    failures = 0
    for case in args.cases:
        expected_path = case.with_suffix(".expected")
        actual = actual_output(args.tracer, case)
        if args.update:
            expected_path.write_text(actual)
            continue
        expected = expected_path.read_text() if expected_path.exists() else "(missing .expected file)\n"
        if actual != expected:
            failures += 1
            sys.stdout.writelines(
                difflib.unified_diff(expected.splitlines(True), actual.splitlines(True), str(expected_path), "actual")
            )
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
