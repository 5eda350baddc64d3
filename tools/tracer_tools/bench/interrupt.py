"""tools/bench interrupt: how long tracer takes to exit after Ctrl-C (SIGINT) in the middle of a
render, at 1024 x 1024 and 8192 x 8192, for each sampling mode (one sample, 2 x 2 samples,
adaptive). Each figure is the median of --runs interrupts, from the signal sent to the process
gone; tracer is signalled once its progress line says the render is under way. Writes
docs/bench/interrupt.md."""

import argparse
import datetime
import os
import pty
import signal
import statistics
import subprocess
import threading
import time

from tracer_tools import option_types
from tracer_tools.bench.common import DOCS, ROOT, TRACER, git, machine

SIZES = [1024, 8192]
MODES = {"1 spp": [], "4 spp": ["--samples", "4"], "adaptive": ["--adaptive", "0.05"]}


def interrupt_once(tracer: str, size: int, mode: list[str], output: str) -> float | None:
    """Seconds from SIGINT, sent once the render is under way, to tracer's exit (which must be 130),
    or None if the render finished before the signal came. tracer's stderr is a terminal (a
    pseudo-terminal), so that it draws its progress line."""
    command = [tracer, ROOT / "scenes" / "task2.scn", "-o", output, "--width", size, "--height", size, *mode]
    leader, follower = pty.openpty()
    process = subprocess.Popen([str(c) for c in command], stderr=follower)
    os.close(follower)
    under_way = threading.Event()

    def drain() -> None:  # read all of it, always: a full terminal would stop tracer's writes
        seen = b""
        while True:
            try:
                seen = (seen + os.read(leader, 4096))[-200:]
            except OSError:  # closed: tracer ended
                return
            if b"%" in seen:
                under_way.set()

    reader = threading.Thread(target=drain, daemon=True)
    reader.start()
    while not under_way.wait(0.01):
        if process.poll() is not None:
            raise SystemExit("tracer ended before its progress line")
    sent = time.perf_counter()
    process.send_signal(signal.SIGINT)
    code = process.wait()
    elapsed = time.perf_counter() - sent
    reader.join(5)
    os.close(leader)
    if code == 0:
        return None
    if code != 130:
        raise SystemExit(f"tracer exited {code} after SIGINT, not 130")
    return elapsed


def interrupts(tracer: str, size: int, mode: list[str], output: str, runs: int) -> list[float]:
    """`runs` latencies (renders that finished before their signal are run again, 20 times at most)."""
    times: list[float] = []
    for _ in range(20 * runs):
        if (elapsed := interrupt_once(tracer, size, mode, output)) is not None:
            times.append(elapsed)
        if len(times) == runs:
            return times
    raise SystemExit(f"{size} x {size} {mode}: the render keeps finishing before the signal")


def main() -> int:
    parser = argparse.ArgumentParser(prog="tools/bench interrupt", description=__doc__.split("\n\n")[0])
    parser.add_argument("--runs", type=option_types.whole_number(1, 1000), default=7)
    parser.add_argument(
        "--base", type=option_types.executable_file, help="another tracer to measure alongside, run by run"
    )
    args = parser.parse_args()
    output = str(ROOT / "out" / "bench" / "interrupt.png")
    os.makedirs(os.path.dirname(output), exist_ok=True)
    builds = {"this build": str(TRACER), **({"--base": args.base} if args.base else {})}
    rows = []
    for size in SIZES:
        for name, mode in MODES.items():
            times: dict[str, list[float]] = {build: [] for build in builds}
            for _ in range(args.runs):  # the builds alternated, one interrupt each
                for build, tracer in builds.items():
                    times[build] += interrupts(tracer, size, mode, output, 1)
            for build in builds:
                rows.append((size, name, build, statistics.median(times[build]), max(times[build])))
                print(
                    f"{size} x {size}, {name}, {build}: median {rows[-1][3] * 1000:.0f} ms, "
                    f"worst {rows[-1][4] * 1000:.0f} ms"
                )
    lines = [
        "# Ctrl-C latency",
        "",
        f"`tools/bench interrupt` on {datetime.date.today()}: from SIGINT, sent once tracer's progress line "
        f"shows the render under way (scenes/task2.scn), to the process gone; median and worst of {args.runs} "
        "interrupts, the builds alternated.",
        "",
        f"Machine: {machine()}.",
        "",
        f"Builds: this build ({git('rev-parse', '--short', 'HEAD')}); --base: {args.base or '(none)'}.",
        "",
        "| image | sampling | build | median | worst |",
        "|---|---|---|--:|--:|",
        *(
            f"| {s} x {s} | {name} | {build} | {median * 1000:.0f} ms | {worst * 1000:.0f} ms |"
            for s, name, build, median, worst in rows
        ),
        "",
    ]
    (DOCS / "interrupt.md").write_text("\n".join(lines))
    print(f"wrote {DOCS / 'interrupt.md'}")
    return 0
