"""What the benchmarks share: the checkout's root, the machine line every report opens with, and
tracer_bench's JSON result."""

import datetime
import json
import os
import pathlib
import platform
import subprocess
import sys

from tracer_tools import ROOT

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
