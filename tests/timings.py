#!/usr/bin/env python3
"""The slowest tests of a ctest run beside the committed timing table (tests/timings.md), so that
CI's log shows where its minutes go and which test grew. ctest writes the run's times with
--output-junit; this prints the slowest, each with its committed figure, and the run's total.
With --update it rewrites the preset's table in tests/timings.md from this run instead.

Usage: tests/timings.py PRESET JUNIT_XML [--table tests/timings.md] [--update] [--count N]"""

import argparse
import pathlib
import re
import signal
import sys
import xml.etree.ElementTree as ElementTree

ROOT = pathlib.Path(__file__).resolve().parents[1]
ROW = re.compile(r"^\| `([^`]+)` \| ([0-9.]+) \|$")
TOTAL = re.compile(r"^(\d+) tests, (\d+) s of test time in all\.$")


def run_times(junit: pathlib.Path) -> dict[str, float]:
    """Each test's seconds in the run, by name."""
    tree = ElementTree.parse(junit)
    return {case.get("name"): float(case.get("time") or 0) for case in tree.iter("testcase")}


def committed_times(table: pathlib.Path, preset: str) -> tuple[dict[str, float], float | None]:
    """The preset's section of the committed table: seconds by test name, and the total."""
    times, total, inside = {}, None, False
    for line in table.read_text(encoding="utf-8").splitlines() if table.is_file() else []:
        if line.startswith("## "):
            inside = line[3:].strip() == preset
        elif inside and (match := ROW.match(line)):
            times[match.group(1)] = float(match.group(2))
        elif inside and (match := TOTAL.match(line)):
            total = float(match.group(2))
    return times, total


def section(preset: str, times: dict[str, float], count: int) -> str:
    """The preset's section of the table: its slowest tests and its total."""
    slowest = sorted(times.items(), key=lambda item: -item[1])[:count]
    rows = "".join(f"| `{name}` | {seconds:.1f} |\n" for name, seconds in slowest)
    total = sum(times.values())
    return (
        f"## {preset}\n\n{len(times)} tests, {total:.0f} s of test time in all.\n\n"
        f"| test | seconds |\n|---|--:|\n{rows}"
    )


def update(table: pathlib.Path, preset: str, text: str) -> None:
    """Replaces (or adds) the preset's section of the table."""
    old = table.read_text(encoding="utf-8") if table.is_file() else ""
    parts = re.split(r"(?m)^(?=## )", old)
    head, sections = parts[0], [part for part in parts[1:] if not part.startswith(f"## {preset}\n")]
    sections.append(text)
    sections.sort(key=lambda part: part.splitlines()[0])
    table.write_text(head + "\n".join(part.rstrip("\n") + "\n" for part in sections), encoding="utf-8")


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="timings.py", description=__doc__.splitlines()[0])
    parser.add_argument("preset", help="the ctest preset the run used (release, debug, float)")
    parser.add_argument("junit", type=pathlib.Path, help="the run's --output-junit file")
    parser.add_argument("--table", type=pathlib.Path, default=ROOT / "tests" / "timings.md")
    parser.add_argument("--update", action="store_true", help="rewrite the preset's table from this run")
    parser.add_argument("--count", type=int, default=12, help="how many of the slowest to show (default 12)")
    arguments = parser.parse_args(argv)
    if arguments.count < 1:
        parser.error("--count must be at least 1")
    try:
        times = run_times(arguments.junit)
    except (OSError, ElementTree.ParseError) as error:
        print(f"timings.py: error: cannot read {arguments.junit}: {error}", file=sys.stderr)
        return 2
    if arguments.update:
        update(arguments.table, arguments.preset, section(arguments.preset, times, arguments.count))
        print(f"timings.py: wrote the {arguments.preset} table of {arguments.table}", file=sys.stderr)
        return 0
    committed, committed_total = committed_times(arguments.table, arguments.preset)
    print(f"ci: the slowest tests of the {arguments.preset} run (seconds; committed in tests/timings.md):")
    for name, seconds in sorted(times.items(), key=lambda item: -item[1])[: arguments.count]:
        was = f"{committed[name]:7.1f}" if name in committed else "      -"
        print(f"  {seconds:7.1f} {was}  {name}")
    was = f"{committed_total:7.0f}" if committed_total is not None else "      -"
    print(f"  {sum(times.values()):7.0f} {was}  (the {len(times)} tests' time in all)")
    return 0


if __name__ == "__main__":
    signal.signal(signal.SIGPIPE, signal.SIG_DFL)  # a reader that stops early (| head) ends it quietly
    sys.exit(main())
