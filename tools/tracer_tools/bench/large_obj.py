"""The large-OBJ benchmark of the hostile-input issue: a valid OBJ of about 100 MB (2.5 million
triangles) loads, builds and renders task2's frame; wall time and peak memory of the whole
`tracer` process, and the time to refuse garbage, special files and oversized requests.
Writes docs/bench/large-obj.md.

    tools/bench large-obj [--runs 3]

The mesh is a wavy height field of 1,119 x 1,119 vertices (2,499,848 triangles) written to
out/bench/large/wave.obj, standing behind task2's spheres in task2's 1200 x 800 frame.
"""

from __future__ import annotations

import argparse
import datetime
import math
import pathlib
import statistics
import subprocess
import sys

from tracer_tools import ROOT, option_types
from tracer_tools.bench.common import machine

TRACER = ROOT / "build" / "release" / "tracer"
OUT = ROOT / "out" / "bench" / "large"
SIDE = 1119  # vertices per side: 2 (SIDE - 1)^2 = 2,499,848 triangles


def write_mesh(path: pathlib.Path) -> None:
    with open(path, "w") as f:
        f.write(f"# wavy height field, {SIDE} x {SIDE} vertices (tools/bench large-obj)\n")
        for j in range(SIDE):
            y = j / (SIDE - 1)
            f.write(
                "".join(
                    f"v {i / (SIDE - 1):.6f} {y:.6f} {0.03 * math.sin(40 * i / SIDE) * math.cos(30 * y):.6f}\n"
                    for i in range(SIDE)
                )
            )
        for j in range(SIDE - 1):
            rows = []
            for i in range(SIDE - 1):
                a = j * SIDE + i + 1
                rows.append(f"f {a} {a + 1} {a + SIDE + 1}\nf {a} {a + SIDE + 1} {a + SIDE}\n")
            f.write("".join(rows))


def timed(args: list) -> tuple[int, float, int]:
    """(exit code, wall seconds, peak resident MB) of one tracer run in a fresh process."""
    code = (
        "import resource, subprocess, sys, time\n"
        "t = time.monotonic(); r = subprocess.run(sys.argv[1:], capture_output=True)\n"
        "print(r.returncode, time.monotonic() - t, resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss // 1024)\n"
    )
    out = subprocess.run([sys.executable, "-c", code, str(TRACER), *map(str, args)], capture_output=True, text=True)
    rc, seconds, megabytes = out.stdout.split()
    return int(rc), float(seconds), int(megabytes)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--runs", type=option_types.whole_number(1, 1_000_000), default=3)
    args = parser.parse_args()
    OUT.mkdir(parents=True, exist_ok=True)
    mesh = OUT / "wave.obj"
    if not mesh.exists():
        write_mesh(mesh)
    scene = OUT / "task2_wave.scn"
    task2 = (ROOT / "scenes" / "task2.scn").read_text()
    scene.write_text(
        task2 + '\nmesh { file "wave.obj" scale (8, 4, 1) translate (-4, -1, -2.9)\n'
        "       material { ka 0.1 kd (0.8, 0.6, 0.2) ks 0.5 n 20 } }\n"
    )

    runs = [timed([scene, "-o", OUT / "task2_wave.png", "-q"]) for _ in range(args.runs)]
    assert all(rc == 0 for rc, _, _ in runs), runs
    seconds = statistics.median(s for _, s, _ in runs)
    megabytes = max(m for _, _, m in runs)

    # Refusals: each must come back at once with a message.
    garbage = OUT / "garbage.obj"
    garbage.write_bytes(bytes(range(256)) * 4096)
    garbage_scene = OUT / "garbage.scn"
    garbage_scene.write_text(
        'camera { eye (0, 0, 7) lookat (0, 0, 0) }\nmesh { file "garbage.obj" material { kd 1 } }\n'
    )
    big = OUT / "sparse_2g.obj"
    with open(big, "wb") as f:
        f.truncate(2 << 30)
    big_scene = OUT / "big.scn"
    big_scene.write_text('camera { eye (0, 0, 7) lookat (0, 0, 0) }\nmesh { file "sparse_2g.obj" material { kd 1 } }\n')
    refusals = [
        ("binary garbage as OBJ", ["--check", garbage_scene]),
        ("/dev/zero as scene", ["--check", "/dev/zero"]),
        ("a 2 GiB OBJ", ["--check", big_scene]),
        (
            "a 16384 x 16384 image",
            [ROOT / "scenes" / "task2.scn", "-o", OUT / "x.png", "--width", "16384", "--height", "16384"],
        ),
    ]
    refused = [(name, *timed(command)) for name, command in refusals]
    big.unlink()

    size = mesh.stat().st_size / 1e6
    lines = [
        "# A large OBJ, and refusals (tools/bench large-obj)",
        "",
        f"Measured {datetime.date.today()} on {machine()}; `tracer` at its default threads.",
        "",
        f"- `task2.scn` plus `{mesh.name}`: {size:.0f} MB, {2 * (SIDE - 1) ** 2:,} triangles; "
        f"read, checked, triangulated, BVH built and rendered at 1200 x 800 in **{seconds:.2f} s** "
        f"(median of {args.runs} runs: {', '.join(f'{s:.2f}' for _, s, _ in runs)}), "
        f"peak resident memory **{megabytes} MB** (target: 20 s and 2 GB).",
        "",
        "| refused input | exit code | seconds | peak MB |",
        "|---|---|---|---|",
        *[f"| {name} | {rc} | {s:.2f} | {m} |" for name, rc, s, m in refused],
        "",
    ]
    (ROOT / "docs" / "bench" / "large-obj.md").write_text("\n".join(lines))
    print("\n".join(lines))


if __name__ == "__main__":
    main()
