"""Issue 56's speed against error for soft shadows: the lamp and the window-lit room
(scenes/lights/lamp.scn, window.scn) at 320 x 240, each area light rendered on the grid, jittered
and adaptive (on the grid and jittered) at several sample counts, against the same light as a 64 x 64 grid (the
reference). Error is the RMSE and the share of pixels more than 2 levels off the reference;
cost is the render time (median of --runs, 2 threads) and the shadow rays traced. * marks the
front (no other variant of the scene is both faster and nearer the reference). Target: adaptive
sampling reaches the 8 x 8 grid's error with at most 1/3 of its shadow rays, on both scenes.

    tools/bench soft-shadows [--runs 3]

Writes docs/bench/speed-vs-error-soft-shadows.md and .png (the report says the machine).
"""

import argparse
import pathlib
import re
import statistics
import tempfile

import numpy as np

from tracer_tools import ROOT, option_types
from tracer_tools.bench.common import DOCS, provenance
from tracer_tools.xcheck import metrics, tracer_cli

SCENES = ("lamp", "window")
VARIANTS = [("grid", n) for n in (4, 8, 12, 16)] + [("jitter", n) for n in (4, 8, 16)]
VARIANTS += [("adaptive", n) for n in (8, 16, 24)] + [("adaptive jitter", n) for n in (4, 5, 6, 7, 8, 16)]
REFERENCE = 64
WIDTH = 320


def with_light(scene: pathlib.Path, folder: pathlib.Path, mode: str, n: int) -> pathlib.Path:
    """The scene with its area light sampled `mode` (grid, jitter, adaptive, adaptive jitter) at n x n."""
    words = {"grid": "", "jitter": " jitter true", "adaptive": " adaptive true"}.get(mode, " adaptive true jitter true")
    text, count = re.subn(r"samples1 \d+ samples2 \d+", f"samples1 {n} samples2 {n}{words}", scene.read_text(), count=1)
    assert count == 1, scene
    out = folder / f"{scene.stem}-{mode.replace(' ', '-')}-{n}.scn"
    out.write_text(text)
    return out


def measure(scene: pathlib.Path, runs: int) -> tuple[np.ndarray, float, int]:
    """The image (linear floats), the median render time and the shadow rays of the scene."""
    times, shadow = [], 0
    for _ in range(runs):
        image, stats = tracer_cli.render_pixels(scene, ["--width", str(WIDTH), "--threads", "2"])
        times.append(stats["render_seconds"])
        shadow = stats["rays"]["shadow"]
    return image, statistics.median(times), shadow


def front(rows: list[dict]) -> None:
    """Marks the rows no other row beats on both time and RMSE."""
    for row in rows:
        row["front"] = not any(
            o["seconds"] <= row["seconds"]
            and o["rmse"] < row["rmse"]
            or o["seconds"] < row["seconds"]
            and o["rmse"] <= row["rmse"]
            for o in rows
        )


def table(name: str, rows: list[dict], reference_seconds: float) -> list[str]:
    lines = [
        f"### {name} (reference: 64 x 64 grid, {reference_seconds:.2f} s)",
        "",
        "| variant | time (s) | shadow rays (M) | RMSE | pixels over 2 levels | front |",
        "|---|---:|---:|---:|---:|:-:|",
    ]
    for r in rows:
        lines.append(
            f"| {r['mode']} {r['n']} x {r['n']} | {r['seconds']:.3f} | {r['shadow'] / 1e6:.2f} | {r['rmse']:.5f} | "
            f"{100 * r['over_2']:.2f}% | {'*' if r['front'] else ''} |"
        )
    return lines + [""]


def target_line(name: str, rows: list[dict]) -> str:
    """The cheapest adaptive variant at the 8 x 8 grid's error or better, against its rays."""
    grid8 = next(r for r in rows if r["mode"] == "grid" and r["n"] == 8)
    good = [r for r in rows if r["mode"].startswith("adaptive") and r["rmse"] <= grid8["rmse"]]
    if not good:
        return f"| {name} | no adaptive variant reaches the 8 x 8 grid's RMSE {grid8['rmse']:.5f} | no |"
    best = min(good, key=lambda r: r["shadow"])
    share = best["shadow"] / grid8["shadow"]
    return (
        f"| {name} | {best['mode']} {best['n']} x {best['n']}: RMSE {best['rmse']:.5f} "
        f"(8 x 8 grid: {grid8['rmse']:.5f}) "
        f"with {share:.2f} of its shadow rays ({best['shadow'] / 1e6:.2f} M against {grid8['shadow'] / 1e6:.2f} M) "
        f"| {'yes' if share <= 1 / 3 else 'no'} |"
    )


def plot(results: dict, path: pathlib.Path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    figure, axes = plt.subplots(1, len(results), figsize=(6 * len(results), 4.5))
    for axis, (name, rows) in zip(np.atleast_1d(axes), results.items(), strict=True):
        for mode, marker in (("grid", "o"), ("jitter", "s"), ("adaptive", "^"), ("adaptive jitter", "v")):
            mine = [r for r in rows if r["mode"] == mode]
            axis.plot([r["seconds"] for r in mine], [r["rmse"] for r in mine], marker=marker, label=mode)
            for r in mine:
                axis.annotate(f"{r['n']}", (r["seconds"], r["rmse"]), textcoords="offset points", xytext=(4, 4))
        axis.set_xscale("log")
        axis.set_yscale("log")
        axis.set_xlabel("render time (s, 2 threads, 320 x 240)")
        axis.set_ylabel("RMSE against the 64 x 64 grid")
        axis.set_title(name)
        axis.legend()
    figure.tight_layout()
    figure.savefig(path, dpi=90)


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--runs", type=option_types.whole_number(1, 100), default=3)
    args = parser.parse_args()
    results, references = {}, {}
    with tempfile.TemporaryDirectory() as name:
        folder = pathlib.Path(name)
        for scene_name in SCENES:
            scene = ROOT / "scenes" / "lights" / f"{scene_name}.scn"
            reference, references[scene_name], _ = measure(with_light(scene, folder, "grid", REFERENCE), 1)
            rows = []
            for mode, n in VARIANTS:
                image, seconds, shadow = measure(with_light(scene, folder, mode, n), args.runs)
                c = metrics.compare(reference, image)
                rows.append(
                    {"mode": mode, "n": n, "seconds": seconds, "shadow": shadow, "rmse": c.rmse, "over_2": c.over_2}
                )
                print(f"{scene_name} {mode} {n}: {seconds:.3f} s, {shadow} shadow rays, RMSE {c.rmse:.5f}", flush=True)
            front(rows)
            results[scene_name] = rows
    facts = provenance()
    lines = [
        "# Speed against error: soft shadows",
        "",
        "<!-- generated by tools/bench soft-shadows -->",
        "",
        f"Machine: {facts['machine']}; {facts['date']}, commit {facts['commit']}; 2 threads; median of {args.runs} "
        f"runs each; {WIDTH} x 240.",
        "",
        "![time against error](speed-vs-error-soft-shadows.png)",
        "",
        "| target: adaptive reaches the 8 x 8 grid's error with at most 1/3 of its shadow rays | measured | met |",
        "|---|---|---|",
    ]
    lines += [target_line(name, rows) for name, rows in results.items()] + [""]
    for name, rows in results.items():
        lines += table(f"scenes/lights/{name}.scn", rows, references[name])
    (DOCS / "speed-vs-error-soft-shadows.md").write_text("\n".join(lines))
    plot(results, DOCS / "speed-vs-error-soft-shadows.png")
    print("\n".join(lines))
    return 0
