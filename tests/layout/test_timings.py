"""tests/timings.py, which CI runs after each ctest run: the table it writes and what it prints."""

import pathlib
import subprocess
import sys

SCRIPT = pathlib.Path(__file__).resolve().parents[1] / "timings.py"
JUNIT = """<?xml version="1.0" encoding="UTF-8"?>
<testsuite name="Test" tests="3">
  <testcase name="slow" classname="slow" time="12.5" status="run"/>
  <testcase name="quick" classname="quick" time="0.25" status="run"/>
  <testcase name="middling" classname="middling" time="3" status="run"/>
</testsuite>
"""


def timings(*arguments) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, SCRIPT, *map(str, arguments)], capture_output=True, text=True)


def test_the_table_is_written_then_shown_beside_a_new_run(tmp_path):
    junit, table = tmp_path / "run.xml", tmp_path / "timings.md"
    junit.write_text(JUNIT)
    table.write_text("# Test timings\n\n## release\n\nold\n")
    assert timings("debug", junit, "--table", table, "--update", "--count", 2).returncode == 0
    text = table.read_text()
    assert "## release\n\nold\n" in text  # other presets' sections kept
    assert "## debug\n\n3 tests, 16 s of test time in all." in text
    assert "| `slow` | 12.5 |\n| `middling` | 3.0 |\n" in text and "quick" not in text

    junit.write_text(JUNIT.replace('time="12.5"', 'time="20"'))
    shown = timings("debug", junit, "--table", table, "--count", 3)
    assert shown.returncode == 0
    lines = shown.stdout.splitlines()
    assert lines[1].split() == ["20.0", "12.5", "slow"]
    assert lines[3].split() == ["0.2", "-", "quick"]  # not in the committed table
    assert lines[4].split()[:2] == ["23", "16"]


def test_an_unreadable_run_is_an_error_without_a_traceback(tmp_path):
    result = timings("debug", tmp_path / "missing.xml")
    assert result.returncode == 2
    assert "cannot read" in result.stderr and "Traceback" not in result.stderr
