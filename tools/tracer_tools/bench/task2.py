"""Renders scenes/task2.scn (1200x800, 1 sample per pixel) several times and reports the median
render time and throughput, as tracer's summary line prints them (render only: parsing, start-up
and the PNG write are not included). Output as committed in docs/bench/bench-task2.txt.

    tools/bench task2 [--runs 9] [--threads N]      defaults: 9 runs, every core
"""

import argparse
import datetime
import os
import re
import statistics
import subprocess
import tempfile

from tracer_tools import ROOT, option_types
from tracer_tools.bench.common import TRACER, machine


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--runs", type=option_types.whole_number(1, 1_000_000), default=9)
    parser.add_argument("--threads", type=option_types.whole_number(0, 4096), default=os.cpu_count())
    args = parser.parse_args()
    if not TRACER.exists():
        subprocess.run([ROOT / "tools" / "bootstrap"], check=True, stdout=subprocess.DEVNULL)
    commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], capture_output=True, text=True, cwd=ROOT)
    print(f"# tools/bench task2: {datetime.date.today()}, {commit.stdout.strip()}")
    print(f"# machine: {machine()}; threads used: {args.threads}; release preset (-O3 -march=native)")
    lines = []
    with tempfile.TemporaryDirectory() as folder:
        for _ in range(args.runs):
            command = [TRACER, ROOT / "scenes" / "task2.scn", "-o", os.path.join(folder, "task2.png")]
            result = subprocess.run(command + ["--threads", str(args.threads)], capture_output=True, text=True)
            result.check_returncode()
            summary = result.stderr.strip().splitlines()[-1].split("task2.png: ")[-1]
            print(f"  {summary}", flush=True)
            lines.append(summary)
    seconds = [float(re.search(r", ([0-9.]+) s,", line).group(1)) for line in lines]
    mrays = [float(re.search(r"([0-9.]+) Mrays/s", line).group(1)) for line in lines]
    print(
        f"median render time {statistics.median(seconds):.3f} s (min {min(seconds):.3f}, max {max(seconds):.3f}), "
        f"median {statistics.median(mrays):.1f} Mrays/s over {len(lines)} runs"
    )
    return 0
