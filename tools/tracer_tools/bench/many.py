"""The many-object benchmark: build time, render time, memory and the ratio to Embree on
scenes of many objects, measured side by side. Writes docs/bench/many-objects-data-Nt.json,
docs/bench/many-objects-tables-Nt.md and docs/bench/many-objects-Nt.png (N = threads);
docs/bench/many-objects.md discusses them.

    tools/bench many                    # everything at 2 threads (about 10 minutes)
    tools/bench many --quick            # fewer pairs and runs, for a try
    tools/bench many --report-only      # rewrite the tables and chart from the saved data
    tools/bench many --shared PATH      # where embree-whitted lives (default ../shared)

Scenes (tools/make-scene many-objects, written to out/bench/many/, 800x600, 1 sample):
  spheres N   N spheres on a grid over a floor, three large mirror spheres behind
              (N = 16, 4,096, 65,536, 10^6)
  bunnies N   N instances of the bunny (one OBJ file), on a floor with two mirror spheres
              (N = 1, 64, 4,096); also with every instance flattened into one merged mesh
              (tracer_bench --flatten), the alternative instancing is measured against

Each pair runs tracer_bench (in-process build and render loop, medians of R renders) and
Embree's embree_scene (the same scene, rays and image, from tracer --dump-json) one after the
other; a ratio is the median of the per-pair ratios, tracer / Embree (> 1: tracer slower).
The bunny scenes alternate the instanced and the flattened tracer with Embree in the same
pairs. Memory is tracer's acceleration structures (top level, meshes), as tracer_bench
reports it. Without embree_scene (no ../shared, or no Debian Embree) the Embree columns are
left empty and said so.
"""

from __future__ import annotations

import argparse
import pathlib
import statistics
import subprocess
import sys

from tracer_tools import ROOT, option_types
from tracer_tools.bench.common import TRACER_BENCH, report_main, run_json

BENCH = TRACER_BENCH
TRACER = ROOT / "build" / "release" / "tracer"
OUT = ROOT / "out" / "bench" / "many"
SPHERES = [16, 4096, 65536, 1000000]
BUNNIES = [1, 64, 4096]


def scene(kind: str, count: int) -> tuple:
    """The scene file and its JSON for embree_scene, written once."""
    OUT.mkdir(parents=True, exist_ok=True)
    path = OUT / f"{kind}_{count}.scn"
    if not path.exists():
        subprocess.run(
            [
                sys.executable,
                "-m",
                "tracer_tools.scenes.many_objects",
                kind,
                "--count",
                str(count),
                "-o",
                path,
                "--obj",
                ROOT / "scenes" / "meshes" / "bunny.obj",
            ],
            check=True,
            stdout=subprocess.DEVNULL,
        )
    dump = path.with_suffix(".json")
    if not dump.exists():
        with open(dump, "w") as out:
            subprocess.run([TRACER, "--dump-json", path], check=True, stdout=out)
    return path, dump


def measure(args: argparse.Namespace, kind: str, count: int, embree: pathlib.Path | None) -> dict:
    """Pairs of runs: tracer (instanced), tracer --flatten (bunnies only), Embree."""
    path, dump = scene(kind, count)
    heavy = (kind == "bunnies" and count >= 1000) or count >= 100000
    runs = str(3 if heavy else args.runs)
    pairs = min(args.pairs, 3) if heavy else args.pairs
    variants = {"tracer": [BENCH, path, "--threads", args.threads, "--runs", runs, "--json"]}
    if kind == "bunnies":
        variants["flattened"] = variants["tracer"] + ["--flatten"]
    if embree:
        variants["embree"] = [embree, dump, "--threads", args.threads, "--runs", runs, "--json"]
    rounds = {name: [] for name in variants}
    for _ in range(pairs):
        for name, command in variants.items():
            rounds[name].append(run_json(command))
    result = {"kind": kind, "count": count, "pairs": pairs, "runs": int(runs)}
    for name, runs_of in rounds.items():
        last = runs_of[-1]
        result[name] = {
            "render_ms": statistics.median(r["render_ms_median"] for r in runs_of),
            "build_ms": statistics.median(r["build_ms"] for r in runs_of),
            "rays": last["rays"],
            "triangles": last.get("triangles", 0),
            "memory_bytes": last.get("memory_bytes"),
            "render_ms_all": [r["render_ms_median"] for r in runs_of],
            "build_ms_all": [r["build_ms"] for r in runs_of],
        }
        if name != "tracer":
            ratios = [
                a["render_ms_median"] / b["render_ms_median"] for a, b in zip(rounds["tracer"], runs_of, strict=True)
            ]
            builds = [
                a["build_ms"] / b["build_ms"]
                for a, b in zip(rounds["tracer"], runs_of, strict=True)
                if b["build_ms"] > 0
            ]
            result[name]["tracer_over_this_render"] = statistics.median(ratios)
            result[name]["tracer_over_this_build"] = statistics.median(builds) if builds else None
    t = result["tracer"]
    t["ns_per_ray"] = t["render_ms"] * 1e6 / t["rays"]
    print(
        f"{kind} {count}: tracer render {t['render_ms']:.1f} ms, build {t['build_ms']:.2f} ms, "
        f"{t['ns_per_ray']:.1f} ns/ray, {t['memory_bytes'] / 2**20:.2f} MiB"
        + (f"; /Embree render {result['embree']['tracer_over_this_render']:.2f}" if "embree" in result else ""),
        flush=True,
    )
    return result


def cell(value: float | None, form: str = "{:.2f}") -> str:
    return "-" if value is None else form.format(value)


def write_report(results: dict, path_md: pathlib.Path, path_png: pathlib.Path) -> None:
    lines = [
        f"<!-- Written by tools/bench many on {results['date']}; do not edit by hand. -->",
        "",
        "## Measured figures: many objects",
        "",
        f"Machine: {results['machine']}. Threads: {results['threads']}. Scenes 800x600, 1 sample "
        "(tools/make-scene many-objects). Each cell: the median over alternating pairs (tracer, "
        "[tracer flattened,] Embree) of each run's median render; ratios are medians of per-pair "
        "ratios, tracer / other (> 1: tracer slower). Memory: tracer's acceleration structures.",
        "",
    ]
    if not results["embree"]:
        lines += ["Embree's embree_scene was not available: its columns are empty.", ""]
    spheres = [r for r in results["scenes"] if r["kind"] == "spheres"]
    base = spheres[0]["tracer"]["ns_per_ray"] if spheres else None
    lines += [
        "### Spheres",
        "",
        "| spheres | rays | tracer render ms | ns per ray | per ray vs 16 | tracer build ms | memory MiB "
        "| Embree render ms | Embree build ms | render tracer/Embree | build tracer/Embree |",
        "|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|",
    ]
    for r in spheres:
        t, e = r["tracer"], r.get("embree", {})
        lines.append(
            f"| {r['count'] + 3:,} | {t['rays']:,} | {t['render_ms']:.1f} | {t['ns_per_ray']:.1f} | "
            f"{t['ns_per_ray'] / base:.2f}x | {t['build_ms']:.2f} | {t['memory_bytes'] / 2**20:.2f} | "
            f"{cell(e.get('render_ms'), '{:.1f}')} | {cell(e.get('build_ms'))} | "
            f"{cell(e.get('tracer_over_this_render'))} | {cell(e.get('tracer_over_this_build'))} |"
        )
    lines += [
        "",
        "(Each scene has three large mirror spheres besides the grid, counted here.)",
        "",
        "### Bunny instances",
        "",
        "| bunnies | triangles | tracer render ms | build ms | memory MiB | flattened render ms | build ms "
        "| memory MiB | instanced/flattened render | Embree render ms | Embree build ms "
        "| render tracer/Embree | build tracer/Embree |",
        "|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|",
    ]
    for r in (r for r in results["scenes"] if r["kind"] == "bunnies"):
        t, f, e = r["tracer"], r["flattened"], r.get("embree", {})
        lines.append(
            f"| {r['count']:,} | {t['triangles']:,} | {t['render_ms']:.1f} | {t['build_ms']:.2f} | "
            f"{t['memory_bytes'] / 2**20:.2f} | {f['render_ms']:.1f} | {f['build_ms']:.1f} | "
            f"{f['memory_bytes'] / 2**20:.1f} | {f['tracer_over_this_render']:.2f} | "
            f"{cell(e.get('render_ms'), '{:.1f}')} | {cell(e.get('build_ms'), '{:.1f}')} | "
            f"{cell(e.get('tracer_over_this_render'))} | {cell(e.get('tracer_over_this_build'), '{:.3f}')} |"
        )
    path_md.write_text("\n".join(lines) + "\n")
    try:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("matplotlib missing (tools/bootstrap --python makes .venv with it): no chart written")
        return
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.2))
    counts = [r["count"] + 3 for r in spheres]
    axes[0].plot(counts, [r["tracer"]["ns_per_ray"] for r in spheres], "o-", label="tracer")
    if results["embree"]:
        axes[0].plot(
            counts, [r["embree"]["render_ms"] * 1e6 / r["embree"]["rays"] for r in spheres], "s--", label="Embree"
        )
    axes[0].set(xscale="log", xlabel="spheres", ylabel="ns per ray (2 threads, wall)", title="Spheres", ylim=(0, None))
    bunnies = [r for r in results["scenes"] if r["kind"] == "bunnies"]
    counts = [r["count"] for r in bunnies]
    axes[1].plot(counts, [r["tracer"]["render_ms"] for r in bunnies], "o-", label="tracer, instanced")
    axes[1].plot(counts, [r["flattened"]["render_ms"] for r in bunnies], "^:", label="tracer, flattened")
    if results["embree"]:
        axes[1].plot(counts, [r["embree"]["render_ms"] for r in bunnies], "s--", label="Embree (flat)")
    axes[1].set(xscale="log", xlabel="bunny instances", ylabel="render ms", title="Bunny instances", ylim=(0, None))
    for ax in axes:
        ax.grid(True, alpha=0.3)
        ax.legend()
    fig.tight_layout()
    fig.savefig(path_png, dpi=90)


def find_embree(args: argparse.Namespace) -> pathlib.Path | None:
    if args.embree:
        return args.embree
    build_sh = args.shared / "bench" / "embree-whitted" / "build.sh"
    if not build_sh.exists():
        print(f"no {build_sh}: the comparison with Embree is skipped")
        return None
    build_dir = ROOT / "out" / "embree-whitted"
    if subprocess.run([build_sh, build_dir], stdout=subprocess.DEVNULL).returncode != 0:
        print("embree-whitted did not build (see its message above): the comparison with Embree is skipped")
        return None
    return build_dir / "embree_scene"


def measure_all(args: argparse.Namespace) -> dict:
    """Every sphere and bunny scene's figures, with Embree's where embree_scene is."""
    embree = find_embree(args)
    results = {"embree": bool(embree), "scenes": []}
    for count in SPHERES:
        results["scenes"].append(measure(args, "spheres", count, embree))
    for count in BUNNIES:
        results["scenes"].append(measure(args, "bunnies", count, embree))
    return results


def main() -> int:
    def add_arguments(parser: argparse.ArgumentParser) -> None:
        parser.add_argument("--shared", type=option_types.existing_folder, default=ROOT.parent / "shared")
        parser.add_argument(
            "--embree", type=option_types.existing_path, help="embree_scene (default: built from --shared)"
        )

    return report_main("many-objects", __doc__, measure_all, write_report, add_arguments)


if __name__ == "__main__":
    sys.exit(main())
