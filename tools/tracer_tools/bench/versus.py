"""tracer against its two peers in one run, on the scenes of issue 35's table: Embree 3's
single-ray kernels (render and build; compare_scene.py of the Embree anchor alternates
tracer_bench and embree_scene, A B A B, medians of the per-pair ratios; the builds of scenes given
as files again alone, 21 a run, with a one-pixel render) and POV-Ray 3.7 (its
reported Trace Time against tracer's render time, alternated the same way), 2 threads.
Embree's anchor has no refraction and no cones: gears and mount are compared with it without kt
and ior, rings and tree with their cones tessellated (tools/nff2scn --cones mesh from the SPD's
NFF under --shared), and say so; POV-Ray renders the scenes whole, cones analytic. The table
goes to standard output (as committed in docs/bench/bench-versus.md); its figures to
docs/bench/bench-versus-data.json and a chart of them, each ratio against its target, to
docs/bench/bench-versus.png.

    tools/bench versus [--shared ../shared] [--pairs 3] [--runs 5] [--scenes task2,balls,...]
    tools/bench versus --report-only      # redraw the chart from the saved figures
"""

import argparse
import json
import pathlib
import re
import statistics
import subprocess
import tempfile

from tracer_tools import ROOT, option_types
from tracer_tools.bench.common import DOCS, TRACER, TRACER_BENCH, alternated, git, machine, run_json
from tracer_tools.nff import nff2scn
from tracer_tools.spd import steps

# name: (scene as compare_scene.py takes it, POV-Ray too?)
SCENES = {
    "task2": ("scenes/task2.scn", True),
    "bunny": ("scenes/bunny.scn", False),
    "bunny_room": ("scenes/bunny_room.scn", False),
    "bunnies_64": ("bunnies_64", False),
    "spheres_4096": ("spheres_4096", False),
    **{
        name: (f"scenes/spd/{name}.scn", True)
        for name in ("balls", "gears", "mount", "rings", "teapot", "tetra", "tree")
    },
}
THREADS = 2
DATA = DOCS / "bench-versus-data.json"
CHART = DOCS / "bench-versus.png"
# column: (its title on the chart, issue 35's target: tracer's time at most this times the peer's)
TARGETS = {
    "render": ("render / Embree 3 single rays", 0.7),
    "build": ("build / Embree 3", 1.0),
    "trace": ("trace / POV-Ray 3.7", 0.2),
}


def tracer_summary_line(scene: pathlib.Path, folder: pathlib.Path) -> str:
    """The summary line of a render of the scene (size, time, rays)."""
    done = subprocess.run(
        [str(TRACER), str(scene), "-o", str(folder / "tracer.png"), "--threads", str(THREADS)],
        capture_output=True,
        text=True,
        check=True,
    )
    return done.stderr.strip().splitlines()[-1]


def tracer_render_seconds(scene: pathlib.Path, folder: pathlib.Path) -> float:
    """tracer's render time of the scene (the summary line's: the render loop alone)."""
    return float(re.search(r", ([0-9.]+) s, ", tracer_summary_line(scene, folder)).group(1))


def versus_povray(scene: pathlib.Path, pairs: int, folder: pathlib.Path) -> dict:
    """Median of the per-pair ratios tracer render / POV-Ray trace, alternating."""
    from tracer_tools.xcheck import povray, tracer_cli

    description = tracer_cli.dump_json(scene)
    times = alternated(
        lambda: tracer_render_seconds(scene, folder),
        lambda: povray.render_scene(description, folder)[1]["trace_seconds"],
        pairs,
    )
    return {"ratio": times["ratio"], "tracer_s": times["a"], "povray_s": times["b"]}


BUILD_RUNS = 21  # builds per run of the build-only comparison (sub-millisecond builds spread widely)


def builds_alone(scene: pathlib.Path, embree_scene: pathlib.Path, pairs: int, folder: pathlib.Path) -> float:
    """Median of the per-pair ratios tracer build / Embree build, alternating, each a median of
    BUILD_RUNS builds with a one-pixel render (the builds alone: compare_scene.py's runs are
    few, being renders too)."""
    from tracer_tools.xcheck import tracer_cli

    description = folder / "builds.json"
    description.write_text(json.dumps(tracer_cli.dump_json(scene)))
    alone = ["--crop", "0 0 1 1", "--threads", str(THREADS), "--runs", str(BUILD_RUNS), "--json"]
    ratios = []
    for _ in range(pairs):
        ours = run_json([TRACER_BENCH, scene, *alone])
        theirs = run_json([embree_scene, description, *alone])
        ratios.append(ours["build_ms"] / theirs["build_ms"])
    return statistics.median(ratios)


def bunny_crop(embree_bench: pathlib.Path, pairs: int, runs: int) -> dict:
    """The bunny's hit-dominated crop: tracer_bench against embree_bench single rays and 16-wide
    packets, alternating (medians of the per-round ratios)."""
    crop = ["--crop", "auto", "--threads", str(THREADS), "--runs", str(runs), "--json"]
    single, packets, build = [], [], []
    for _ in range(pairs):
        one = run_json([embree_bench, *crop])
        ours = run_json([TRACER_BENCH, ROOT / "scenes" / "bunny.scn", *crop])
        sixteen = run_json([embree_bench, "--packet", "16", *crop])
        single.append(ours["render_ms_median"] / one["render_ms_median"])
        packets.append(ours["render_ms_median"] / sixteen["render_ms_median"])
        build.append(ours["build_ms"] / one["build_ms"])
    return {
        "single": statistics.median(single),
        "packets": statistics.median(packets),
        "build": statistics.median(build),
    }


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--shared", type=option_types.existing_folder, default=ROOT.parent / "shared")
    parser.add_argument("--pairs", type=option_types.whole_number(1, 1_000_000), default=3)
    parser.add_argument("--runs", type=option_types.whole_number(1, 1_000_000), default=5)
    parser.add_argument("--scenes", type=option_types.free_text, default=",".join(SCENES))
    parser.add_argument("--report-only", action="store_true", help="redraw the chart from the saved figures")
    args = parser.parse_args()
    if args.report_only:
        draw_chart(json.loads(DATA.read_text()), CHART)
        return 0
    bench_folder = args.shared / "bench" / "embree-whitted"
    if not bench_folder.is_dir():
        parser.error(f"no Embree anchor at {bench_folder} (give --shared)")
    embree = steps.build_embree(bench_folder, ROOT / "build" / "spd" / "embree")
    print(f"# tools/bench versus: {git('log', '-1', '--format=%cs')}, {git('rev-parse', '--short', 'HEAD')}")
    print(
        f"# machine: {machine()}; threads used: {THREADS}; release preset (-O3 -march=native); "
        f"{args.pairs} pairs, {args.runs} runs each\n"
    )
    figures = {"commit": git("rev-parse", "--short", "HEAD"), "machine": machine(), "rows": []}
    print("| scene | render vs Embree single-ray | build vs Embree | trace vs POV-Ray 3.7 | tracer / POV-Ray s |")
    print("|---|--:|--:|--:|--:|")
    with tempfile.TemporaryDirectory() as temporary:
        folder = pathlib.Path(temporary)
        for name in args.scenes.split(","):
            scene, with_povray = SCENES[name]
            embree_scene, note = scene, ""
            if name in ("gears", "mount"):
                copy = ROOT / "scenes" / "spd" / f".{name}_no_refraction.scn"  # beside it: its meshes' paths
                steps.without_refraction(ROOT / scene, copy)
                embree_scene, note = str(copy), " (Embree: refraction off)"
            if name in ("rings", "tree"):
                tessellated = folder / f"{name}_tessellated.scn"
                nff2scn.convert_file(args.shared / "spd" / "nff" / f"{name}.nff", tessellated, cones="mesh")
                embree_scene, note = str(tessellated), " (Embree: cones tessellated in both)"
            try:
                found = steps.compare_with_embree(
                    bench_folder, embree, embree_scene, args.pairs, args.runs, folder / "compare.json"
                )
                build_ratio = found.get("build_ratio")
                if embree_scene.endswith(".scn"):  # (compare_scene.py makes the named ones itself)
                    build_ratio = builds_alone(ROOT / embree_scene, embree, args.pairs, folder)
            finally:
                if note:
                    pathlib.Path(embree_scene).unlink(missing_ok=True)  # (the tessellated meshes go with folder)
            render = f"{found['render_ratio']:.2f}" if "render_ratio" in found else "refused"
            build = f"{build_ratio:.2f}" if build_ratio is not None else "–"
            trace = times = "–"
            if with_povray:
                peer = versus_povray(ROOT / scene, args.pairs, folder)
                trace, times = f"{peer['ratio']:.2f}", f"{peer['tracer_s']:.3f} / {peer['povray_s']:.2f}"
            print(f"| {name}{note} | {render} | {build} | {trace} | {times} |", flush=True)
            figures["rows"].append(
                {
                    "scene": name + note,
                    "render": found.get("render_ratio"),
                    "build": build_ratio,
                    "trace": peer["ratio"] if with_povray else None,
                }
            )
            (folder / "compare.json").unlink(missing_ok=True)
            if name == "bunny":
                crop = bunny_crop(embree.parent / "embree_bench", args.pairs, args.runs)
                print(
                    f"| bunny, hit-dominated crop | {crop['single']:.2f} ({crop['packets']:.2f} against 16-wide "
                    f"packets) | {crop['build']:.2f} | – | – |",
                    flush=True,
                )
                figures["rows"].append(
                    {
                        "scene": "bunny, hit-dominated crop",
                        "render": crop["single"],
                        "build": crop["build"],
                        "trace": None,
                        "render_vs_packets": crop["packets"],
                    }
                )
    print(
        "\nRatios are tracer's time over the peer's (below 1: tracer is faster); issue 35's targets: render "
        "≤ 0.7 (the crop ≤ 1.0 against packets), build ≤ 1.0, trace ≤ 0.2."
    )
    if set(args.scenes.split(",")) == set(SCENES):  # a partial run leaves the committed figures alone
        DATA.write_text(json.dumps(figures, indent=1) + "\n")
        draw_chart(figures, CHART)
    return 0


def draw_chart(figures: dict, path: pathlib.Path) -> None:
    """One panel per column: each scene's ratio as a bar, the target as a line (bars past it in red)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    rows = figures["rows"]
    fig, axes = plt.subplots(1, 3, figsize=(13, 5.2), sharey=True)
    names = [row["scene"].split(" (")[0] for row in rows]
    for ax, (column, (title, target)) in zip(axes, TARGETS.items(), strict=True):
        values = [row[column] for row in rows]
        for y, value in enumerate(values):
            if value is not None:
                ax.barh(y, value, color="tab:green" if value <= target else "tab:red")
                ax.text(value, y, f" {value:.2f}", va="center", fontsize=8)
        ax.axvline(target, color="black", linestyle="--", linewidth=1)
        ax.axvline(1.0, color="grey", linewidth=0.6)
        ax.set(title=f"{title}\n(target ≤ {target})", xlabel="ratio (below 1: tracer faster)")
        ax.set_xlim(0, max([v for v in values if v is not None] + [target]) * 1.25)
        ax.grid(True, axis="x", alpha=0.3)
    axes[0].set_yticks(range(len(names)), names)
    axes[0].invert_yaxis()
    fig.suptitle(
        f"tracer against Embree 3 and POV-Ray 3.7, 2 threads ({figures['commit']}; {figures['machine'][:40]})",
        fontsize=10,
    )
    fig.tight_layout()
    fig.savefig(path, dpi=90)
