"""Issue 58's targets for the Python package, side by side on this machine (2 threads):

1. `import tracer` in a fresh interpreter (the import alone, timed inside it), median of 21
   (target: at most 50 ms);
2. task2 loaded and rendered from Python (tracer.load + Scene.render in a warm interpreter)
   against the command line's own load, world and render seconds (--stats-json) for the same
   image, alternated A B A B (target: at most 1.02);
3. the peak memory of a 4096 x 4096 render of task2 above the loaded scene's (the kernel's
   high-water mark before and after the render), against the image's own size as float32
   (target: at most 1.1).

    tools/bench python [--pairs 7]

The package is imported from build/release/python (tools/test builds it there). The report goes
to standard output, as committed in docs/bench/bench-python.md.
"""

import json
import os
import statistics
import subprocess
import sys
import tempfile
from pathlib import Path

from tracer_tools import ROOT
from tracer_tools.bench.common import TRACER, alternated, targets_main

THREADS = 2
PACKAGE = ROOT / "build" / "release" / "python"
TASK2 = ROOT / "scenes" / "task2.scn"

IMPORT = "import time; t = time.perf_counter(); import tracer; print(time.perf_counter() - t)"
PEAK = """
import sys, tracer
def high_water():
    for line in open("/proc/self/status"):
        if line.startswith("VmHWM:"):
            return int(line.split()[1]) * 1024
scene = tracer.load(sys.argv[1])
scene.render(width=8, height=8)  # NumPy imported and the threads made: the scene's side
before = high_water()
pixels = scene.render(width=4096, height=4096, threads=2)
print(before, high_water(), pixels.nbytes)
"""
# Load and render in one warm interpreter, as many times as asked on stdin, each answer its seconds.
SERVER = """
import sys, time, tracer
tracer.load(sys.argv[1]).render(width=8)  # warm: NumPy imported, threads made
for line in sys.stdin:
    start = time.perf_counter()
    tracer.load(sys.argv[1]).render(threads=2)
    print(time.perf_counter() - start, flush=True)
"""


def python_env() -> dict:
    return dict(os.environ, PYTHONPATH=str(PACKAGE))


def import_seconds(runs: int = 21) -> list[float]:
    """`import tracer` timed inside `runs` fresh interpreters."""
    times = []
    for _ in range(runs):
        out = subprocess.run([sys.executable, "-c", IMPORT], capture_output=True, text=True, env=python_env())
        out.check_returncode()
        times.append(float(out.stdout))
    return times


def command_line_seconds(folder: str) -> float:
    """The command line's load + world + render seconds for task2 (its own --stats-json figures)."""
    stats = Path(folder) / "stats.json"
    command = [TRACER, TASK2, "-o", Path(folder) / "task2.exr", "--quiet", "--threads", str(THREADS)]
    subprocess.run([str(c) for c in command] + ["--stats-json", str(stats)], check=True)
    figures = json.loads(stats.read_text())
    return figures["load_seconds"] + figures["world_seconds"] + figures["render_seconds"]


def main() -> int:
    args = targets_main("python", __doc__, THREADS)
    if not (PACKAGE / "tracer").is_dir():
        print(f"tools/bench python: no package in {PACKAGE}: run tools/test first", file=sys.stderr)
        return 1
    # 1. The import.
    imports = import_seconds()
    print(
        f"1. import tracer: median {statistics.median(imports) * 1000:.1f} ms (min {min(imports) * 1000:.1f}) "
        f"over {len(imports)} fresh interpreters (target 50 ms)"
    )
    # 2. Load + render from Python against the command line's.
    server = subprocess.Popen(
        [sys.executable, "-c", SERVER, str(TASK2)],
        stdin=subprocess.PIPE,
        stdout=subprocess.PIPE,
        text=True,
        env=python_env(),
    )

    def from_python() -> float:
        server.stdin.write("go\n")
        server.stdin.flush()
        return float(server.stdout.readline())

    with tempfile.TemporaryDirectory() as folder:
        pairs = alternated(from_python, lambda: command_line_seconds(folder), args.pairs)
    server.stdin.close()
    server.wait()
    print(
        f"2. task2 load + render: Python {pairs['a']:.3f} s, command line {pairs['b']:.3f} s (load, world, "
        f"render); median ratio {pairs['ratio']:.3f} (target 1.02); ratios "
        + " ".join(f"{r:.3f}" for r in pairs["ratios"])
    )
    # 3. Memory of a 4096 x 4096 render.
    out = subprocess.run([sys.executable, "-c", PEAK, str(TASK2)], capture_output=True, text=True, env=python_env())
    out.check_returncode()
    before, after, image = (int(v) for v in out.stdout.split())
    print(
        f"3. 4096 x 4096 render: peak {before / 2**20:.0f} MiB before, {after / 2**20:.0f} MiB after; "
        f"{(after - before) / 2**20:.0f} MiB above the scene's for a {image / 2**20:.0f} MiB image: "
        f"{(after - before) / image:.3f} of its size (target 1.1)"
    )
    return 0


if __name__ == "__main__":
    sys.exit(main())
