"""Single-mesh scenes against an earlier build: the many-objects issue's target "no slower than
before the two-level world" (docs/bench/many-objects.md).

Builds tracer_bench three ways: BASE (a commit, default 1f57b86, the first wave's last build) in
a git worktree under build/, the current tree with BASE's rules (TRACER_ROBUST=OFF:
Moller-Trumbore, t-min 1e-4) in build/single-mesh-naive, and the current tree's default
(build/release). Then times task2, bunny_room, the bunny's full frame and its crop with each
(2 threads, median of 5 renders per run), the three in turn, the order reversed every other
round (the machine's speed drifts); ratios are medians of per-round ratios to BASE. Writes
docs/bench/single-mesh-data.json and docs/bench/single-mesh.md.

    tools/bench single-mesh                # about 8 minutes on 2 cores
    tools/bench single-mesh --rounds 5 --base 1f57b86
    tools/bench single-mesh --report-only  # rewrite the table from the JSON
"""

import argparse
import json
import statistics
import sys

from tracer_tools import ROOT, option_types
from tracer_tools.bench.common import base_build, build, git, provenance, run_json

DOCS = ROOT / "docs" / "bench"
SCENES = {  # name: tracer_bench arguments
    "task2": ["scenes/task2.scn"],
    "bunny_room": ["scenes/bunny_room.scn"],
    "bunny, full frame": ["scenes/bunny.scn"],
    "bunny, crop": ["scenes/bunny.scn", "--crop", "auto"],
}


def measure(builds: dict, rounds: int, runs: int, threads: int) -> dict:
    times = {scene: {name: [] for name in builds} for scene in SCENES}
    for round_index in range(rounds):
        order = list(builds) if round_index % 2 == 0 else list(reversed(builds))
        for scene, arguments in SCENES.items():
            for name in order:
                command = [builds[name], *arguments, "--threads", threads, "--runs", runs, "--json"]
                times[scene][name].append(run_json(command)["render_ms_median"])
        print(f"round {round_index + 1}/{rounds} done", file=sys.stderr)
    return times


def write_report(results: dict) -> None:
    names = list(results["builds"])
    base = names[0]
    lines = [
        f"Machine: {results['machine']}. Measured {results['date']} at {results['commit']}; base "
        f"{results['base']}; tracer_bench, {results['threads']} threads, medians of {results['rounds']} rounds of "
        f"{results['runs']} renders, the builds alternating.",
        "",
        "| scene | " + " | ".join(names) + " |",
        "|---|" + "---:|" * len(names),
    ]
    for scene, times in results["times"].items():
        cells = []
        for name in names:
            ratio = statistics.median(b / a for a, b in zip(times[base], times[name], strict=True))
            cells.append(f"{statistics.median(times[name]):.2f} ms ({ratio:.3f}x)")
        lines.append(f"| {scene} | " + " | ".join(cells) + " |")
    lines += ["", "Render time, and in brackets its median per-round ratio to the base build.", ""]
    for name, what in results["builds"].items():
        lines.append(f"- {name}: {what}")
    (DOCS / "single-mesh.md").write_text(
        "# Single-mesh scenes against the first wave's last build\n\n"
        "Written by `tools/bench single-mesh` (the many-objects issue's target: single-mesh scenes no "
        "slower than before the two-level world; docs/bench/many-objects.md).\n\n" + "\n".join(lines) + "\n"
    )


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--base", type=option_types.free_text, default="1f57b86")
    parser.add_argument("--rounds", type=option_types.whole_number(1, 1_000_000), default=9)
    parser.add_argument("--runs", type=option_types.whole_number(1, 1_000_000), default=5)
    parser.add_argument("--threads", type=option_types.whole_number(0, 4096), default=2)
    parser.add_argument("--report-only", action="store_true")
    args = parser.parse_args()
    data = DOCS / "single-mesh-data.json"
    if args.report_only:
        write_report(json.loads(data.read_text()))
        return 0
    base = git("rev-parse", "--short", args.base)
    builds = {
        f"base {base}": base_build(base),
        "naive rules (TRACER_ROBUST=OFF)": build(ROOT, ROOT / "build" / "single-mesh-naive", "-DTRACER_ROBUST=OFF"),
        "default (robust rules)": build(ROOT, ROOT / "build" / "release"),
    }
    results = {
        **provenance(),
        "base": base,
        "threads": args.threads,
        "rounds": args.rounds,
        "runs": args.runs,
        "builds": {
            f"base {base}": f"commit {base} as it was (its own rules, Moller-Trumbore and t-min 1e-4)",
            "naive rules (TRACER_ROBUST=OFF)": "this tree with the base's rules",
            "default (robust rules)": "this tree as shipped (watertight triangles, error-bounded spawn points)",
        },
        "times": measure(builds, args.rounds, args.runs, args.threads),
    }
    data.write_text(json.dumps(results, indent=1) + "\n")
    write_report(results)
    print((DOCS / "single-mesh.md").read_text())
    return 0


if __name__ == "__main__":
    sys.exit(main())
