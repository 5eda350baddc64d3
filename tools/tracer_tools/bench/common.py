"""What the benchmarks share: the checkout's root, the machine line every report opens with, and
tracer_bench's JSON result, the command line of the benchmarks that keep their figures."""

import argparse
import datetime
import json
import os
import pathlib
import platform
import statistics
import subprocess
import sys
from collections.abc import Callable

from tracer_tools import ROOT, option_types

BUILD = ROOT / "build" / "release"
TRACER = BUILD / "tracer"
TRACER_BENCH = BUILD / "tracer_bench"
DOCS = ROOT / "docs" / "bench"
OUT = ROOT / "out" / "bench"


def run_json(command: list) -> dict:
    """Runs `command` in the checkout's root and returns the last JSON object it printed; exits on failure."""
    result = subprocess.run([str(c) for c in command], capture_output=True, text=True, cwd=ROOT)
    if result.returncode != 0:
        sys.exit(f"failed: {' '.join(map(str, command))}\n{result.stderr}")
    return json.loads([line for line in result.stdout.splitlines() if line.startswith("{")][-1])


def machine() -> str:
    """The processor, core count, system and compiler, as each report states them."""
    model = next(
        (line.split(":", 1)[1].strip() for line in open("/proc/cpuinfo") if line.startswith("model name")), "?"
    )
    compiler = subprocess.run(["c++", "--version"], capture_output=True, text=True).stdout.splitlines()[0]
    return f"{model}, {os.cpu_count()} cores visible, {platform.system()} {platform.release()}, {compiler}"


def git(*args: str) -> str:
    """What `git ARGS` prints in the checkout, stripped."""
    return subprocess.run(["git", *args], cwd=ROOT, check=True, capture_output=True, text=True).stdout.strip()


def build(source: pathlib.Path, folder: pathlib.Path, *options: str) -> pathlib.Path:
    """tracer_bench of the tree at `source`, configured by the release preset, in `folder`."""
    configure = ["cmake", "--preset", "release", "-B", str(folder), *options]
    subprocess.run(configure, cwd=source, check=True, stdout=subprocess.DEVNULL)
    subprocess.run(["cmake", "--build", str(folder), "--target", "tracer_bench"], cwd=source, check=True)
    return folder / "tracer_bench"


def base_build(commit: str) -> pathlib.Path:
    """tracer_bench of `commit`, checked out in a worktree of its own (kept for later runs) and built there."""
    tree = ROOT / "build" / f"base-{commit}"
    if not tree.exists():
        subprocess.run(["git", "worktree", "add", "--detach", str(tree), commit], cwd=ROOT, check=True)
    return build(tree, tree / "build" / "release")


def provenance() -> dict:
    """Where a report's figures come from: the machine, the day and the commit measured."""
    return {
        "machine": machine(),
        "date": datetime.date.today().isoformat(),
        "commit": git("rev-parse", "--short", "HEAD"),
    }


def alternated(first: Callable[[], float], second: Callable[[], float], pairs: int) -> dict:
    """first() and second() alternated `pairs` times (A B A B: a noisy machine's drift falls on
    both): the median of the per-pair ratios first / second, each side's median, the ratios."""
    ratios, a, b = [], [], []
    for _ in range(pairs):
        a.append(first())
        b.append(second())
        ratios.append(a[-1] / b[-1])
    return {
        "ratio": statistics.median(ratios),
        "a": statistics.median(a),
        "b": statistics.median(b),
        "ratios": ratios,
    }


def targets_main(name: str, description: str, threads: int) -> argparse.Namespace:
    """The command line of a benchmark that prints an issue's targets as a table (--pairs N,
    default 7), and the header its report opens with."""
    parser = argparse.ArgumentParser(description=description, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--pairs", type=option_types.whole_number(1, 1000), default=7)
    args = parser.parse_args()
    print(f"# tools/bench {name}: {datetime.date.today()}, {git('rev-parse', '--short', 'HEAD')}")
    print(f"# machine: {machine()}; {threads} threads; release preset; medians of {args.pairs} alternating pairs\n")
    return args


def report_main(
    name: str,
    description: str,
    measure: Callable[[argparse.Namespace], dict],
    write_report: Callable[[dict, pathlib.Path, pathlib.Path], None],
    add_arguments: Callable[[argparse.ArgumentParser], None] | None = None,
) -> int:
    """The command line of a benchmark that keeps its figures in docs/bench/NAME-data-Nt.json
    and writes NAME-tables-Nt.md and NAME-Nt.png from them (N: threads): --quick (5 renders a
    run, 3 pairs; else 11 and 5), --threads, --report-only (redraw from the saved figures), and
    the benchmark's own options. `measure(args)` gives the figures after the common header."""
    parser = argparse.ArgumentParser(description=description, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--quick", action="store_true", help="5 renders a run and 3 pairs (else 11 and 5)")
    parser.add_argument(
        "--threads", type=option_types.whole_number(0, 4096), default=2, help="render threads (default 2)"
    )
    parser.add_argument("--report-only", action="store_true", help="rewrite the report from the saved data")
    if add_arguments:
        add_arguments(parser)
    args = parser.parse_args()
    if args.threads < 1:
        parser.error("--threads must be at least 1")
    args.runs = 5 if args.quick else 11
    args.pairs = 3 if args.quick else 5
    suffix = f"{args.threads}t"
    data_path = DOCS / f"{name}-data-{suffix}.json"
    if args.report_only:
        results = json.loads(data_path.read_text())
    else:
        if not TRACER_BENCH.exists():
            subprocess.run([ROOT / "tools" / "bootstrap"], check=True)
        results = {
            "date": datetime.date.today().isoformat(),
            "machine": machine(),
            "threads": args.threads,
            "runs": args.runs,
            "pairs": args.pairs,
        }
        results.update(measure(args))
        data_path.write_text(json.dumps(results, indent=1) + "\n")
    tables, chart = DOCS / f"{name}-tables-{suffix}.md", DOCS / f"{name}-{suffix}.png"
    write_report(results, tables, chart)
    print(f"wrote {', '.join(str(path.relative_to(ROOT)) for path in (data_path, tables, chart))}")
    return 0
