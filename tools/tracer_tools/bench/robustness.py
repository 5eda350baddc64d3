"""The G1 table of hard-cases.md: what double precision and robustness cost and buy.

Builds four variants of tracer (CMake TRACER_REAL = double or float, TRACER_ROBUST = ON or OFF)
into build/g1-<variant>, runs each one's hard-case tests (tests/hard_cases, --gtest_output=json)
for the error figures, and times task2, the bunny (its crop) and bunny_room with tracer_bench,
the four variants alternating round by round (the machine's speed drifts; ratios are medians of
per-round ratios to the robust double build). Writes docs/bench/robustness-g1-data.json,
docs/bench/robustness-g1-table.md (copied into docs/bench/speed-vs-error.md) and docs/bench/robustness-g1.png.

    tools/bench robustness              # about 10 minutes on 2 cores
    tools/bench robustness --rounds 3   # quicker, noisier
    tools/bench robustness --report-only  # redraw from the JSON
"""

from __future__ import annotations

import argparse
import datetime
import json
import pathlib
import statistics
import subprocess
import sys

from tracer_tools import ROOT, option_types
from tracer_tools.bench.common import machine, run_json

DOCS = ROOT / "docs" / "bench"
VARIANTS = {  # name: (TRACER_REAL, TRACER_ROBUST)
    "double robust": ("double", "ON"),
    "double naive": ("double", "OFF"),
    "float robust": ("float", "ON"),
    "float naive": ("float", "OFF"),
}
BASELINE = "double robust"
SCENES = {"task2": [], "bunny crop": ["--crop", "auto"], "bunny_room": []}
SCENE_FILES = {"task2": "task2.scn", "bunny crop": "bunny.scn", "bunny_room": "bunny_room.scn"}
# Error figures (RecordProperty names of tests/hard_cases), in the table's order.
FIGURES = [
    ("A1 leaks", ["a1_leaks", "a2_leaks", "a3_leaks", "b_leaks"]),
    ("A1 rays", ["a1_rays", "a2_rays", "a3_rays", "b_rays"]),
    ("A3 misses", ["a3a_misses", "a3b_misses"]),
    ("A5 cube leaks", ["a5_cube_leaks", "a5_cube_obj_leaks"]),
    ("B1 acne (self-occluded points)", ["b1_d1_self_occluded", "b1_d3_self_occluded", "b1_d5_self_occluded"]),
    ("B2 sphere re-hits", ["b2_sa_rehits", "b2_sb_rehits", "b2_sc_rehits", "b2_sd_rehits"]),
    ("soup self-hits (10^7 rays)", ["soup_placed_self_hits", "soup_instanced_self_hits"]),
    (
        "B4 lights on surfaces: NaN pixels / self-occlusions / floor lit by L1",
        ["b4_non_finite_pixels", "b4_self_occlusions", "b4_floor_pixels_lit_by_l1"],
    ),
    ("C1 misclassified (i / ii)", ["c1_i_misclassified", "c1_ii_misclassified"]),
    ("C1 max t error, ulps (i / ii)", ["c1_i_max_t_error_ulps", "c1_ii_max_t_error_ulps"]),
    (
        "C3 escapes / self-occluded (i / ii)",
        ["c3_i_escapes", "c3_i_self_occluded", "c3_ii_escapes", "c3_ii_self_occluded"],
    ),
    ("C4 mismatches", ["c4_mismatches"]),
    ("D1 wrong (plane / grid)", ["d1_plane_wrong", "d1_grid_wrong"]),
    (
        "E1 leak pixels / self-occlusions / pixels over 4 levels",
        ["e1_leak_pixels", "e1_self_occlusions", "e1_pixels_over_4_levels"],
    ),
    (
        "D2 tie rule broken (blocks, T = 0 / 1e4; one mesh, in order / shuffled)",
        ["d2_i_t0_second_quad_wins", "d2_i_t1e4_second_quad_wins", "d2_mesh_wrong", "d2_mesh_shuffled_wrong"],
    ),
    (
        "D2 upper quad seen (1e-3, 1e-5, 1e-3 at 1e4)",
        ["d2_ii_1e-3_upper_fraction", "d2_ii_1e-5_upper_fraction", "d2_ii_1e-3_at_1e4_upper_fraction"],
    ),
    ("F1 reflections (291 exact)", ["f1_mirror_reflections"]),
    ("F1 max relative drift", ["f1_max_relative_drift"]),
    (
        "scale 1e-4 / 1e4: pixels over 2 levels",
        [
            "scale_task2_1e-4_pixels_over_2_levels",
            "scale_task2_1e4_pixels_over_2_levels",
            "scale_bunny_room_1e-4_pixels_over_2_levels",
            "scale_bunny_room_1e4_pixels_over_2_levels",
        ],
    ),
]


def build_dir(variant: str) -> pathlib.Path:
    return ROOT / "build" / ("g1-" + variant.replace(" ", "-"))


def build(variant: str) -> None:
    real, robust = VARIANTS[variant]
    folder = build_dir(variant)
    subprocess.run(
        ["cmake", "--preset", "release", "-B", folder, f"-DTRACER_REAL={real}", f"-DTRACER_ROBUST={robust}"],
        cwd=ROOT,
        check=True,
        stdout=subprocess.DEVNULL,
    )
    subprocess.run(["cmake", "--build", folder, "--target", "tracer_bench", "hard_cases_tests"], cwd=ROOT, check=True)


def hard_case_figures(variant: str) -> dict:
    """Every figure the hard-case tests record, and which tests failed."""
    out = build_dir(variant) / "hard_cases.json"
    subprocess.run(
        [build_dir(variant) / "hard_cases_tests", f"--gtest_output=json:{out}"], cwd=ROOT, stdout=subprocess.DEVNULL
    )
    report = json.loads(out.read_text())
    figures, failed, tests = {}, [], 0
    for suite in report["testsuites"]:
        for test in suite["testsuite"]:
            tests += 1
            if test.get("failures"):
                failed.append(test["name"])
            for key, value in test.items():
                if key not in (
                    "name",
                    "status",
                    "result",
                    "timestamp",
                    "time",
                    "classname",
                    "failures",
                    "file",
                    "line",
                ):
                    try:
                        figures[key] = float(value)
                    except (TypeError, ValueError):
                        pass
    return {"figures": figures, "failed_tests": failed, "tests": tests}


def measure_times(args: argparse.Namespace) -> dict:
    """Render times: every variant once per round, rounds alternating."""
    times = {v: {f"{s}/{t}t": [] for s in SCENES for t in args.threads} for v in VARIANTS}
    for _ in range(args.rounds):
        for scene, extra in SCENES.items():
            for threads in args.threads:
                for variant in VARIANTS:
                    command = [
                        build_dir(variant) / "tracer_bench",
                        ROOT / "scenes" / SCENE_FILES[scene],
                        "--threads",
                        threads,
                        "--runs",
                        args.runs,
                        "--json",
                        *extra,
                    ]
                    times[variant][f"{scene}/{threads}t"].append(run_json(command))
    out = {}
    for variant, by_key in times.items():
        out[variant] = {}
        for key, runs in by_key.items():
            base = times[BASELINE][key]
            out[variant][key] = {
                "render_ms_median": statistics.median(r["render_ms_median"] for r in runs),
                "ratio_to_baseline": statistics.median(
                    r["render_ms_median"] / b["render_ms_median"] for r, b in zip(runs, base, strict=True)
                ),
                "mrays_per_s": statistics.median(r["mrays_per_s"] for r in runs),
                "build_ms": statistics.median(r["build_ms"] for r in runs),
                "memory_bytes": runs[-1]["memory_bytes"],
            }
    return out


def write_report(results: dict) -> None:
    variants = list(VARIANTS)
    lines = [
        f"Machine: {results['machine']}. Measured {results['date']}; tracer_bench, medians of "
        f"{results['rounds']} rounds of {results['runs']} renders, the variants alternating.",
        "",
    ]
    # Speed.
    lines += ["| scene, threads | " + " | ".join(variants) + " |", "|---|" + "---:|" * len(variants)]
    for key in results["times"][BASELINE]:
        cells = []
        for v in variants:
            t = results["times"][v][key]
            cells.append(f"{t['render_ms_median']:.1f} ms ({t['ratio_to_baseline']:.2f}x)")
        lines.append(f"| {key} | " + " | ".join(cells) + " |")
    lines += ["", "Render time, and in brackets its median ratio to the robust double build, round by round.", ""]
    # Error.
    lines += ["| hard case | " + " | ".join(variants) + " |", "|---|" + "---:|" * len(variants)]
    for label, keys in FIGURES:
        cells = []
        for v in variants:
            figures = results["errors"][v]["figures"]
            values = [figures.get(k) for k in keys]
            cells.append(" / ".join("?" if x is None else f"{x:g}" for x in values))
        lines.append(f"| {label} | " + " | ".join(cells) + " |")
    lines += [
        "",
        "Hard-case tests failing: "
        + "; ".join(f"{v}: {', '.join(results['errors'][v]['failed_tests']) or 'none'}" for v in variants)
        + ".",
    ]
    table = "\n".join(lines) + "\n"
    (DOCS / "robustness-g1-table.md").write_text(table)
    # The same table in speed-vs-error.md, between its markers.
    doc = DOCS / "speed-vs-error.md"
    begin, end = (
        "<!-- generated by tools/bench robustness: begin -->",
        "<!-- generated by tools/bench robustness: end -->",
    )
    text = doc.read_text()
    if begin in text and end in text:
        head, rest = text.split(begin, 1)
        doc.write_text(head + begin + "\n\n" + table + "\n" + end + rest.split(end, 1)[1])
    plot(results)


def plot(results: dict) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    variants = list(VARIANTS)
    keys = list(results["times"][BASELINE])
    fig, (speed, error) = plt.subplots(1, 2, figsize=(11, 4), gridspec_kw={"width_ratios": [3, 2]})
    width = 0.8 / len(variants)
    for i, v in enumerate(variants):
        speed.bar(
            [k + i * width for k in range(len(keys))],
            [results["times"][v][key]["ratio_to_baseline"] for key in keys],
            width,
            label=v,
        )
    speed.set_xticks([k + 0.4 - width / 2 for k in range(len(keys))], keys, rotation=20, fontsize=8)
    speed.axhline(1.0, color="black", linewidth=0.5)
    speed.set_ylabel("render time / robust double")
    speed.set_title("Speed")
    speed.legend(fontsize=8)
    # Error: the mean render-time ratio against the hard-case tests each build fails.
    for v in variants:
        ratio = statistics.median(results["times"][v][key]["ratio_to_baseline"] for key in keys)
        failed = len(results["errors"][v]["failed_tests"])
        error.scatter(ratio, failed, s=60)
        error.annotate(v, (ratio, failed), textcoords="offset points", xytext=(6, 4), fontsize=8)
    error.set_xlabel("median render time / robust double")
    error.set_ylabel(f"hard-case tests failed (of {results['errors'][BASELINE]['tests']})")
    error.set_title("Speed against error")
    fig.tight_layout()
    fig.savefig(DOCS / "robustness-g1.png", dpi=100)


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--rounds", type=option_types.whole_number(1, 1_000_000), default=7)
    parser.add_argument("--runs", type=option_types.whole_number(1, 1_000_000), default=5)
    parser.add_argument("--threads", type=option_types.whole_number(0, 4096), nargs="+", default=[1, 2])
    parser.add_argument("--report-only", action="store_true")
    args = parser.parse_args()
    data = DOCS / "robustness-g1-data.json"
    if args.report_only:
        write_report(json.loads(data.read_text()))
        return 0
    for variant in VARIANTS:
        build(variant)
    results = {
        "machine": machine(),
        "date": datetime.date.today().isoformat(),
        "rounds": args.rounds,
        "runs": args.runs,
        "errors": {v: hard_case_figures(v) for v in VARIANTS},
        "times": measure_times(args),
    }
    data.write_text(json.dumps(results, indent=1) + "\n")
    write_report(results)
    print((DOCS / "robustness-g1-table.md").read_text())
    return 0


if __name__ == "__main__":
    sys.exit(main())
