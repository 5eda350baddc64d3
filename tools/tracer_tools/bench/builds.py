"""This tree against an earlier commit, side by side, on the scenes of the single-mesh and
many-objects benchmarks: render and build times of tracer_bench (2 threads, median of 5 renders
per run), the two builds in turn and the order reversed every other round (the machine's speed
drifts); ratios are medians of per-round ratios, this tree / BASE. For a change that must not
move any figure (a refactoring): the report says how far each moved.

    tools/bench builds --base 7b0e3aa --report docs/bench/house-bench.md     # about 10 minutes
"""

import argparse
import json
import pathlib
import statistics
import subprocess
import sys

from tracer_tools import ROOT, option_types
from tracer_tools.bench.common import OUT, base_build, build, git, provenance, run_json

# name: (tracer_bench arguments, which benchmark the scene comes from)
SCENES = {
    "task2": (["scenes/task2.scn"], "single-mesh"),
    "bunny_room": (["scenes/bunny_room.scn"], "single-mesh"),
    "bunny, full frame": (["scenes/bunny.scn"], "single-mesh"),
    "bunny, crop": (["scenes/bunny.scn", "--crop", "auto"], "single-mesh"),
    "4,099 spheres": (["scenes/many_spheres.scn"], "many-objects"),
    "65,539 spheres": ([str(OUT / "many" / "spheres_65536.scn")], "many-objects"),
    "64 bunnies": (["scenes/bunnies.scn"], "many-objects"),
}


def make_scenes() -> None:
    """The generated scene of the list, written as tools/bench many writes it."""
    path = OUT / "many" / "spheres_65536.scn"
    if not path.exists():
        path.parent.mkdir(parents=True, exist_ok=True)
        command = [sys.executable, "-m", "tracer_tools.scenes.many_objects", "spheres", "--count", "65536"]
        subprocess.run([*command, "-o", str(path)], check=True, stdout=subprocess.DEVNULL)


def measure(builds: dict, rounds: int, runs: int, threads: int) -> dict:
    """Per scene and build: the render and build times of every round."""
    times = {scene: {name: {"render": [], "build": []} for name in builds} for scene in SCENES}
    for round_index in range(rounds):
        order = list(builds) if round_index % 2 == 0 else list(reversed(builds))
        for scene, (arguments, _) in SCENES.items():
            for name in order:
                command = [builds[name], *arguments, "--threads", threads, "--runs", runs, "--json"]
                result = run_json(command)
                times[scene][name]["render"].append(result["render_ms_median"])
                times[scene][name]["build"].append(result["build_ms"])
        print(f"round {round_index + 1}/{rounds} done", file=sys.stderr)
    return times


def write_report(results: dict, path: pathlib.Path) -> None:
    """The table of both builds' times and the ratios, as Markdown."""
    base, head = list(results["builds"])
    lines = [
        f"# This tree ({results['commit']}) against {results['base']}",
        "",
        "Written by `tools/bench builds`. "
        f"Machine: {results['machine']}. Measured {results['date']}; tracer_bench, {results['threads']} "
        f"threads, {results['rounds']} rounds of {results['runs']} renders, the builds alternating.",
        "",
        "| scene | from | render, base | render, this tree | ratio | build ratio |",
        "|---|---|--:|--:|--:|--:|",
    ]
    for scene, by_build in results["times"].items():
        ratio = {
            part: statistics.median(
                h / b for b, h in zip(by_build[base][part], by_build[head][part], strict=True) if b > 0
            )
            for part in ("render", "build")
        }
        lines.append(
            f"| {scene} | {SCENES[scene][1]} | {statistics.median(by_build[base]['render']):.2f} ms | "
            f"{statistics.median(by_build[head]['render']):.2f} ms | {ratio['render']:.3f} | {ratio['build']:.3f} |"
        )
    lines += ["", "Ratios: medians of per-round ratios, this tree / base (below 1: this tree faster)."]
    path.write_text("\n".join(lines) + "\n")


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--base", type=option_types.free_text, required=True, help="the commit to compare with")
    parser.add_argument("--report", type=option_types.output_file, required=True, help="the Markdown file to write")
    parser.add_argument("--rounds", type=option_types.whole_number(1, 1_000_000), default=5)
    parser.add_argument("--runs", type=option_types.whole_number(1, 1_000_000), default=5)
    parser.add_argument("--threads", type=option_types.whole_number(0, 4096), default=2)
    args = parser.parse_args()
    make_scenes()
    base = git("rev-parse", "--short", args.base)
    builds = {f"base {base}": base_build(base), "this tree": build(ROOT, ROOT / "build" / "release")}
    results = {
        **provenance(),
        "base": base,
        "threads": args.threads,
        "rounds": args.rounds,
        "runs": args.runs,
        "builds": {name: str(path) for name, path in builds.items()},
        "times": measure(builds, args.rounds, args.runs, args.threads),
    }
    args.report.with_suffix(".json").write_text(json.dumps(results, indent=1) + "\n")
    write_report(results, args.report)
    print(args.report.read_text())
    return 0
