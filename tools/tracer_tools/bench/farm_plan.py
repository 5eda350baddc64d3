"""tools/bench farm-plan: how long the farm takes to read and plan a long list of jobs (the
issue's 10^5, each of scenes/task2.scn to an output of its own) before it sends any tile: the
jobs file read and validated, then every job checked (tracer run once per distinct scene, each
output folder once, the tracer hashed once). Median of --runs runs in one process each; writes
docs/bench/farm-plan.md."""

import argparse
import datetime
import json
import os
import shutil
import statistics
import subprocess
import sys
import tempfile

from tracer_tools import option_types
from tracer_tools.bench.common import DOCS, ROOT, TRACER, git, machine

# One run, in a fresh interpreter: prints the two times as JSON.
ONE_RUN = """
import json, sys, time
from tracer_tools.farm import farm
from tracer_tools.farm.jobs import jobs_from_file
start = time.perf_counter()
jobs = jobs_from_file(sys.argv[1])
read = time.perf_counter()
farm.check_jobs(sys.argv[2], jobs)
print(json.dumps({"jobs": len(jobs), "read": read - start, "plan": time.perf_counter() - read}))
"""


def main() -> int:
    parser = argparse.ArgumentParser(prog="tools/bench farm-plan", description=__doc__.split("\n\n")[0])
    parser.add_argument("--jobs", type=option_types.whole_number(1, 10**6), default=10**5)
    parser.add_argument("--runs", type=option_types.whole_number(1, 100), default=5)
    args = parser.parse_args()
    folder = tempfile.mkdtemp(prefix="farm-plan-")
    try:
        shutil.copy(ROOT / "scenes" / "task2.scn", folder)
        os.mkdir(f"{folder}/out")
        entries = [{"scene": "task2.scn", "output": f"out/{i}.png", "width": 8} for i in range(args.jobs)]
        jobs_file = f"{folder}/jobs.json"
        with open(jobs_file, "w") as out:
            json.dump(entries, out)
        runs = []
        for _ in range(args.runs):
            result = subprocess.run(
                [sys.executable, "-c", ONE_RUN, jobs_file, str(TRACER)],
                capture_output=True,
                text=True,
                cwd=ROOT / "tools",
            )
            if result.returncode != 0:
                sys.exit(f"farm-plan: a run failed:\n{result.stderr}")
            runs.append(json.loads(result.stdout.splitlines()[-1]))
            print(f"{runs[-1]['jobs']} jobs: read {runs[-1]['read']:.2f} s, planned {runs[-1]['plan']:.2f} s")
    finally:
        shutil.rmtree(folder, ignore_errors=True)
    read = statistics.median(r["read"] for r in runs)
    plan = statistics.median(r["plan"] for r in runs)
    total = statistics.median(r["read"] + r["plan"] for r in runs)
    lines = [
        "# The farm's planning of many jobs",
        "",
        f"`tools/bench farm-plan` on {datetime.date.today()} at {git('rev-parse', '--short', 'HEAD')}: "
        f"{args.jobs} jobs of scenes/task2.scn (8 pixels wide), each to an output of its own in one folder; "
        f"median of {args.runs} runs, each in a fresh interpreter.",
        "",
        f"Machine: {machine()}.",
        "",
        "| step | median |",
        "|---|--:|",
        f"| read and validate the jobs file | {read:.2f} s |",
        f"| check and plan every job | {plan:.2f} s |",
        f"| both (the issue's target: 5 s) | {total:.2f} s |",
        "",
    ]
    (DOCS / "farm-plan.md").write_text("\n".join(lines))
    print(f"wrote {DOCS / 'farm-plan.md'}")
    return 0
