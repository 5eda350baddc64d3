"""The BVH benchmark: build and render times of every accelerator on the bunny and its
subdivisions (3,674 to 940,544 triangles), full frame and hit-dominated crop, and the ratios
to Embree (../shared/bench/embree-whitted) measured side by side. Writes
docs/bench/performance-data-Nt.json, docs/bench/performance-tables-Nt.md and docs/bench/performance-Nt.png
(N = threads). docs/bench/performance.md discusses them.

    tools/bench bvh                      # everything at 2 threads (about 20 minutes)
    tools/bench bvh --threads 1          # the same on one core (steadier)
    tools/bench bvh --quick              # fewer runs and pairs, for a try
    tools/bench bvh --embree PATH        # embree_bench built elsewhere

Times come from tools/bench (tracer_bench): build and render loop timed in-process, medians
of several renders, like embree_bench. Comparisons alternate the programs or accelerators run
by run (A B A B ...) and take the median of the per-pair ratios: on a shared machine only
side-by-side measurements compare. `none` and `box` are not run
where one render would take minutes: their times are extrapolated linearly in the triangle
count from the largest mesh they ran on, and marked so.
"""

from __future__ import annotations

import argparse
import pathlib
import statistics
import subprocess
import sys

from tracer_tools import option_types
from tracer_tools.bench.common import ROOT, TRACER_BENCH, report_main, run_json

BENCH = TRACER_BENCH
SHARED_EMBREE = ROOT.parent / "shared" / "bench" / "embree-whitted"
LEVELS = [0, 1, 2, 3, 4]
TRIANGLES = {0: 3674, 1: 14696, 2: 58784, 3: 235136, 4: 940544}
# Largest subdivision level each accelerator is run on (beyond: extrapolated).
MAX_LEVEL = {"none": 0, "box": 1, "median": 4, "sah": 4}
WORKLOADS = {"full": [], "crop": ["--crop", "auto"]}


def mesh(level: int) -> pathlib.Path:
    path = ROOT / "out" / "bench" / f"bunny_sub{level}.obj"
    if level and not path.exists():
        subprocess.run(
            [
                sys.executable,
                "-m",
                "tracer_tools.scenes.subdivide_obj",
                ROOT / "scenes" / "meshes" / "bunny.obj",
                path,
                "--passes",
                str(level),
            ],
            check=True,
            stdout=subprocess.DEVNULL,
        )
    return path


def tracer_command(level: int, accel: str, workload: str, threads: int, runs: int) -> list:
    command = [BENCH, ROOT / "scenes" / "bunny.scn", "--accel", accel, "--threads", threads, "--runs", runs, "--json"]
    if level:
        command += ["--obj", mesh(level)]
    return command + WORKLOADS[workload]


def embree_command(embree: pathlib.Path, level: int, workload: str, threads: int, runs: int) -> list:
    return [embree, "--subdiv", level, "--threads", threads, "--runs", runs, "--json"] + WORKLOADS[workload]


def measure_accelerators(args: argparse.Namespace, results: dict) -> None:
    """Every accelerator on every mesh; median and sah alternate round by round (the machine's
    speed drifts from minute to minute), and their ratios are medians of per-round ratios."""
    for workload in WORKLOADS:
        for level in LEVELS:
            rounds = {accel: [] for accel in ("none", "box", "median", "sah")}
            for round_index in range(args.pairs):
                for accel in rounds:
                    if level > MAX_LEVEL[accel] or (accel in ("none", "box") and round_index > 0):
                        continue  # baselines: orders of magnitude apart, one run is enough
                    runs = 3 if accel in ("none", "box") else args.runs
                    rounds[accel].append(run_json(tracer_command(level, accel, workload, args.threads, runs)))
            for accel, runs_of_accel in rounds.items():
                key = f"{workload}/{accel}/{level}"
                if not runs_of_accel:
                    base = results["tracer"][f"{workload}/{accel}/{MAX_LEVEL[accel]}"]
                    scale = TRIANGLES[level] / TRIANGLES[MAX_LEVEL[accel]]
                    results["tracer"][key] = {
                        "render_ms_median": base["render_ms_median"] * scale,
                        "build_ms": base["build_ms"] * scale,
                        "extrapolated": True,
                    }
                    continue
                data = dict(runs_of_accel[-1])
                data["render_ms_median"] = statistics.median(r["render_ms_median"] for r in runs_of_accel)
                data["build_ms"] = statistics.median(r["build_ms"] for r in runs_of_accel)
                results["tracer"][key] = data
            ratios = [
                m["render_ms_median"] / s["render_ms_median"]
                for m, s in zip(rounds["median"], rounds["sah"], strict=False)
            ]
            results["tracer"][f"{workload}/median_over_sah/{level}"] = statistics.median(ratios)
            print(
                f"{workload} level {level}: "
                f"sah {results['tracer'][f'{workload}/sah/{level}']['render_ms_median']:.2f} ms, "
                f"median/sah {statistics.median(ratios):.2f}",
                flush=True,
            )


def measure_embree(args: argparse.Namespace, results: dict, embree: pathlib.Path) -> None:
    for workload in WORKLOADS:
        for level in LEVELS:
            render_ratios, build_ratios = [], []
            for _ in range(args.pairs):
                a = run_json(embree_command(embree, level, workload, args.threads, args.runs))
                b = run_json(tracer_command(level, "sah", workload, args.threads, args.runs))
                render_ratios.append(b["render_ms_median"] / a["render_ms_median"])
                build_ratios.append(b["build_ms"] / a["build_ms"])
            key = f"{workload}/{level}"
            results["embree"][key] = {
                "render_ms_median": a["render_ms_median"],
                "build_ms": a["build_ms"],
                "render_ratio": statistics.median(render_ratios),
                "build_ratio": statistics.median(build_ratios),
                "render_ratios": render_ratios,
                "build_ratios": build_ratios,
            }
            print(
                f"embree {key}: sah/embree render {statistics.median(render_ratios):.2f}x, "
                f"build {statistics.median(build_ratios):.2f}x",
                flush=True,
            )


def write_report(results: dict, path_md: pathlib.Path, path_png: pathlib.Path) -> None:
    t = results["tracer"]
    e = results["embree"]
    lines = [
        f"<!-- Written by tools/bench bvh on {results['date']}; do not edit by hand. -->",
        "",
        "## Measured figures",
        "",
        f"Machine: {results['machine']}. Threads: {results['threads']}. "
        f"Medians of {results['runs']} renders per run; ratios to Embree: median of {results['pairs']} "
        "alternating pairs. Times in ms; *italic* = extrapolated linearly from a smaller mesh.",
        "",
    ]
    for workload, title in (
        ("full", "Full frame 1200x800"),
        ("crop", "Hit-dominated crop (the bunny's projected bounds + 4 px)"),
    ):
        lines += [
            f"### {title}",
            "",
            "| triangles | none | box | median | sah | sah build | sah vs box | sah vs median |"
            + (" Embree render | Embree build | sah/Embree render | sah/Embree build |" if e else ""),
            "|---:|---:|---:|---:|---:|---:|---:|---:|" + ("---:|---:|---:|---:|" if e else ""),
        ]
        for level in LEVELS:

            def cell(accel: str, field: str = "render_ms_median", workload: str = workload, level: int = level) -> str:
                r = t[f"{workload}/{accel}/{level}"]
                text = f"{r[field]:.1f}" if r[field] >= 10 else f"{r[field]:.2f}"
                return f"*{text}*" if r.get("extrapolated") else text

            sah = t[f"{workload}/sah/{level}"]["render_ms_median"]
            row = (
                f"| {TRIANGLES[level]:,} | {cell('none')} | {cell('box')} | {cell('median')} | {cell('sah')} | "
                f"{cell('sah', 'build_ms')} | {t[f'{workload}/box/{level}']['render_ms_median'] / sah:.0f}x | "
                f"{t[f'{workload}/median_over_sah/{level}']:.2f}x |"
            )
            if e:
                r = e[f"{workload}/{level}"]
                row += (
                    f" {r['render_ms_median']:.1f} | {r['build_ms']:.1f} | {r['render_ratio']:.2f} | "
                    f"{r['build_ratio']:.2f} |"
                )
            lines.append(row)
        lines.append("")
    lines.append(f"![render and build time against triangle count](performance-{results['threads']}t.png)")
    path_md.write_text("\n".join(lines) + "\n")
    try:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("matplotlib missing (apt-get install python3-matplotlib): no chart written")
        return
    fig, axes = plt.subplots(1, 3, figsize=(15, 4.5))
    counts = [TRIANGLES[level] for level in LEVELS]
    for ax, workload, field, title in (
        (axes[0], "full", "render_ms_median", "render, full frame"),
        (axes[1], "crop", "render_ms_median", "render, crop"),
        (axes[2], "full", "build_ms", "build"),
    ):
        for accel in ["median", "sah"] if field == "build_ms" else ["none", "box", "median", "sah"]:
            values = [t[f"{workload}/{accel}/{level}"][field] for level in LEVELS]
            measured = [not t[f"{workload}/{accel}/{level}"].get("extrapolated") for level in LEVELS]
            ax.plot(counts, values, "-" if all(measured) else "--", marker="o", label=accel)
        if e:
            key = "render_ms_median" if field != "build_ms" else "build_ms"
            ax.plot(counts, [e[f"{workload}/{level}"][key] for level in LEVELS], "k:", marker="s", label="Embree 3")
        ax.set(xscale="log", yscale="log", xlabel="triangles", ylabel="ms", title=title)
        ax.grid(True, which="both", alpha=0.3)
        ax.legend()
    fig.suptitle(f"tracer BVH, bunny 1200x800, {results['threads']} threads ({results['machine'].split(',')[0]})")
    fig.tight_layout()
    fig.savefig(path_png, dpi=90)


def measure(args: argparse.Namespace) -> dict:
    """Every accelerator's figures, and Embree's where embree_bench is (or can be built)."""
    results = {"tracer": {}, "embree": {}}
    embree = args.embree
    if embree is None and (SHARED_EMBREE / "build.sh").exists():
        build_dir = ROOT / "out" / "embree-whitted"
        subprocess.run([SHARED_EMBREE / "build.sh", build_dir], check=True, stdout=subprocess.DEVNULL)
        embree = build_dir / "embree_bench"
    measure_accelerators(args, results)
    if embree:
        measure_embree(args, results, embree)
    else:
        print("no embree_bench: the comparison with Embree is skipped")
    return results


def main() -> int:
    def add_arguments(parser: argparse.ArgumentParser) -> None:
        parser.add_argument(
            "--embree", type=option_types.existing_path, help="embree_bench (default: build ../shared's)"
        )

    return report_main("performance", __doc__, measure, write_report, add_arguments)


if __name__ == "__main__":
    sys.exit(main())
