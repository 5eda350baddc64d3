"""tools/bench flat-shapes: issue 34's figure, 10^6 quads, triangles or boxes from a loop.

    tools/bench flat-shapes [--side 1000] [--runs 7] [--threads 2]

Each kind is written as a side x side loop of shapes and rendered at 64 x 48, --runs times
with the kinds in turn and a pause between runs; a one-shape scene gives the memory the
process takes anyway. Reported: load + build (--stats-json's load_seconds + world_seconds),
median and range; the whole process's time and peak memory (GNU time); the peak per triangle
above the one-shape scene's. Writes docs/bench/bench-flat-shapes.md.
"""

from __future__ import annotations

import argparse
import json
import pathlib
import statistics
import subprocess
import sys
import time

from tracer_tools import option_types

from .common import DOCS, OUT, TRACER, provenance

KINDS = {  # keys of one shape at (i, j), and its triangles
    "quad": ("corner (i, j, 0) edge1 (0.5, 0, 0) edge2 (0, 0.5, 0)", 2),
    "triangle": ("a (i, j, 0) b (i + 0.5, j, 0) c (i, j + 0.5, 0)", 1),
    "box": ("min (i, j, 0) max (i + 0.5, j + 0.5, 0.5)", 12),
}


def scene_text(kind: str, side: int) -> str:
    keys = KINDS[kind][0]
    return (
        f"camera {{ eye ({side / 2}, {side / 2}, {1.4 * side}) lookat ({side / 2}, {side / 2}, 0) }}\n"
        f"light {{ position (0, 0, {1.8 * side}) }}\nmaterial grey {{ kd 1 }}\n"
        f"for i in 0..{side} {{ for j in 0..{side} {{ {kind} {{ {keys} material grey }} }} }}\n"
    )


def run(scene: pathlib.Path, threads: int) -> dict:
    """One render: load + build seconds, the process's seconds and peak kilobytes."""
    stats, timing = OUT / "flat_stats.json", OUT / "flat_time.txt"
    command = ["/usr/bin/time", "-f", "%e %M", "-o", timing, TRACER, scene, "-o", OUT / "flat.png"]
    command += ["--width", "64", "--height", "48", "--threads", threads, "-q", "--stats-json", stats]
    subprocess.run([str(c) for c in command], check=True)
    figures = json.loads(stats.read_text())
    seconds, kilobytes = timing.read_text().split()
    return {
        "load_build": figures["load_seconds"] + figures["world_seconds"],
        "process": float(seconds),
        "peak_kb": int(kilobytes),
    }


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="tools/bench flat-shapes", description=__doc__.split("\n")[0])
    parser.add_argument(
        "--side",
        type=option_types.whole_number(1, 1_000_000),
        default=1000,
        help="shapes per side of the loop (default 10^3)",
    )
    parser.add_argument("--runs", type=option_types.whole_number(1, 1_000_000), default=7)
    parser.add_argument("--threads", type=option_types.whole_number(0, 4096), default=2)
    parser.add_argument("--pause", type=option_types.real_number(0), default=4.0, help="seconds between runs")
    args = parser.parse_args(argv)
    OUT.mkdir(parents=True, exist_ok=True)
    scenes = {}
    for kind in KINDS:
        scenes[kind] = OUT / f"flat_{kind}.scn"
        scenes[kind].write_text(scene_text(kind, args.side))
    one = OUT / "flat_one.scn"
    one.write_text(scene_text("box", 1))
    base_kb = statistics.median(run(one, args.threads)["peak_kb"] for _ in range(3))
    results = {kind: [] for kind in KINDS}
    for round_ in range(args.runs):
        for kind in KINDS:
            time.sleep(args.pause)
            results[kind].append(run(scenes[kind], args.threads))
            print(f"tools/bench flat-shapes: round {round_ + 1} {kind}: {results[kind][-1]}", file=sys.stderr)
    facts = provenance()
    rows = []
    for kind, runs in results.items():
        triangles = KINDS[kind][1] * args.side**2
        load_build = [r["load_build"] for r in runs]
        process = [r["process"] for r in runs]
        peak = max(r["peak_kb"] for r in runs)
        rows.append(
            f"| {kind} | {triangles:,} | {statistics.median(load_build):.2f} s ({min(load_build):.2f}-"
            f"{max(load_build):.2f}) | {statistics.median(process):.2f} s ({min(process):.2f}-{max(process):.2f}) "
            f"| {peak / 1024:.0f} MB | {(peak - base_kb) * 1024 / triangles:.0f} B |"
        )
    (DOCS / "bench-flat-shapes.md").write_text(
        f"""# {args.side ** 2:,} flat shapes from a loop (issue 34)

Measured by `tools/bench flat-shapes` on {facts['date']} at {facts['commit']}: {facts['machine']};
{args.threads} threads, a 64 x 48 render, {args.runs} runs of each kind taken in turn, {args.pause:g} s
apart. Load + build is `--stats-json`'s `load_seconds` + `world_seconds`; the process adds
start-up, the render, the PNG and exit. Per triangle: the peak above a one-box scene's
({base_kb / 1024:.0f} MB). Issue 34's targets: load + build at most 2.5 s, at most 300 bytes per
triangle.

| shapes | triangles | load + build, median (range) | whole process | peak | per triangle |
|---|--:|--:|--:|--:|--:|
{chr(10).join(rows)}
"""
    )
    print(f"tools/bench flat-shapes: wrote {DOCS / 'bench-flat-shapes.md'}", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
