"""What the benchmarks share: the checkout's root, the machine line every report opens with, and
tracer_bench's JSON result."""

import json
import os
import platform
import subprocess
import sys

from tracer_tools import ROOT

BUILD = ROOT / "build" / "release"
TRACER = BUILD / "tracer"
TRACER_BENCH = BUILD / "tracer_bench"
DOCS = ROOT / "docs"
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
