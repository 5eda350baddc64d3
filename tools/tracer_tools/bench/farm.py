"""The render farm's overhead and scaling, measured on this machine, for both of its engines (workers
rendering in their own process with the tracer package, "module", or through tracer processes,
"process"). Writes docs/bench/farm-bench.json and docs/bench/farm-bench.md; docs/farm.md discusses
them.

    tools/bench farm            # about 6 minutes on 2 cores
    tools/bench farm --quick    # one round and a short sweep, for a try

1. Overhead: `tracer --threads 2` and the farm with each engine (a local cluster of 2 workers) render
   the same 10-second image (bunny_room, 121 samples per pixel) one after the other, PAIRS rounds
   (the order turned each round); each is timed as a whole process (start to exit, as a user waits
   for it); the overhead is the median of the per-round ratios farm / tracer, minus one. The
   farm's own timings (--timings) split its time.
2. Per-tile cost: the farm renders a 1.5-second image (16 samples) at tile sizes from 400 to 40
   pixels, both engines alternating, SWEEPS times; the tiles' summed work on the workers grows by a
   fixed cost per tile (least squares over every run of an engine). Each image is compared with
   tracer's own, byte for byte in its pixels.
3. Prediction for N workers (one core each) on a cluster, from the module engine's measured parts:
   start-up, writing and shut-down, the work spread over N, the per-tile cost of 16 tiles per
   worker, half a tile of idling at the end, unless the serial part is longer: Dask's scheduling of
   each tile (measured with no-op tasks), pasting on the client and the tiles' bytes at 1 Gbit/s.
"""

import argparse
import datetime
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time

import tracer_tools
from tracer_tools import option_types

ROOT = str(tracer_tools.ROOT)
TRACER = os.path.join(ROOT, "build", "release", "tracer")
SCENE = os.path.join(ROOT, "scenes", "bunny_room.scn")
LINK_BYTES_PER_S = 125e6  # 1 Gbit/s


def wall(command: list[str], env: dict | None = None) -> float:
    start = time.perf_counter()
    subprocess.run(command, check=True, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    return time.perf_counter() - start


ENGINES = ("process", "module")


def farm_command(output: str, timings: str, engine: str, *extra) -> list[str]:
    return [
        sys.executable,
        "-m",
        "tracer_tools.farm.farm",
        SCENE,
        "-o",
        output,
        "-q",
        "--timings",
        timings,
        "--engine",
        engine,
        *extra,
    ]


def farm_run(folder: str, output: str, engine: str, *extra) -> tuple[float, dict]:
    """One farm run of bunny_room: its whole process's seconds and its --timings."""
    env = {**os.environ, "PYTHONPATH": os.path.join(ROOT, "tools")}
    timings_path = os.path.join(folder, "timings.json")
    seconds = wall(farm_command(os.path.join(folder, output), timings_path, engine, *extra), env)
    with open(timings_path) as file:
        return seconds, json.load(file)


def same_pixels(first: str, second: str) -> bool:
    import numpy as np
    import OpenImageIO as oiio

    def pixels(path: str) -> np.ndarray:
        return oiio.ImageBuf(path).get_pixels(oiio.UINT8)

    return bool(np.array_equal(pixels(first), pixels(second)))


def overhead(pairs: int, folder: str) -> dict:
    """Step 1: tracer alone against the farm with each engine, the order turned each round."""
    rows = []
    alone_path = os.path.join(folder, "alone.png")
    for number in range(pairs):
        row = {}
        runs = ["tracer", *ENGINES]
        for run in runs if number % 2 == 0 else runs[::-1]:
            if run == "tracer":
                command = [TRACER, SCENE, "-o", alone_path, "-q", "--threads", "2", "--samples", "121"]
                row["tracer_s"] = wall(command)
            else:
                seconds, timings = farm_run(folder, f"{run}.png", run, "--samples", "121", "--workers", "2")
                row[run] = {"farm_s": seconds, "timings": timings}
        for engine in ENGINES:
            row[engine]["ratio"] = row[engine]["farm_s"] / row["tracer_s"]
            row[engine]["identical"] = same_pixels(alone_path, os.path.join(folder, f"{engine}.png"))
        rows.append(row)
    result = {"pairs": rows, "median_tracer_s": statistics.median(row["tracer_s"] for row in rows)}
    for engine in ENGINES:
        middle = sorted(rows, key=lambda row: row[engine]["ratio"])[len(rows) // 2][engine]
        result[engine] = {
            "median_ratio": statistics.median(row[engine]["ratio"] for row in rows),
            "median_farm_s": statistics.median(row[engine]["farm_s"] for row in rows),
            "identical": all(row[engine]["identical"] for row in rows),
            "split_of_median_pair": middle["timings"] | {"process_s": middle["farm_s"]},
        }
    return result


def per_tile_cost(tiles: list[int], sweeps: int, folder: str) -> dict:
    """Step 2: the tiles' summed work against their number, for each engine."""
    alone = os.path.join(folder, "sweep-alone.png")
    wall([TRACER, SCENE, "-o", alone, "-q", "--samples", "16"])
    points = {engine: [] for engine in ENGINES}
    for sweep in range(sweeps):
        for tile in tiles:
            for engine in ENGINES if sweep % 2 == 0 else ENGINES[::-1]:
                extra = ["--samples", "16", "--workers", "2", "--tile", str(tile)]
                _, timings = farm_run(folder, f"sweep-{engine}.png", engine, *extra)
                keys = ("tiles", "tile_work_s", "tiles_s", "tile_bytes", "assembly_s")
                point = {"tile": tile, **{key: timings[key] for key in keys}}
                point["identical"] = same_pixels(alone, os.path.join(folder, f"sweep-{engine}.png"))
                points[engine].append(point)
    result = {}
    for engine, found in points.items():
        xs = [point["tiles"] for point in found]
        ys = [point["tile_work_s"] for point in found]
        mean_x, mean_y = statistics.mean(xs), statistics.mean(ys)
        slope = sum((x - mean_x) * (y - mean_y) for x, y in zip(xs, ys, strict=True)) / sum(
            (x - mean_x) ** 2 for x in xs
        )
        assembly = sum(point["assembly_s"] for point in found) / sum(xs)
        result[engine] = {
            "points": found,
            "per_tile_s": slope,
            "assembly_per_tile_s": assembly,
            "work_without_tiles_s": mean_y - slope * mean_x,
        }
    return result


def fixed_cost(calls: int = 200, rounds: int = 5) -> dict:
    """Step 3b: each engine's fixed cost of one task on a worker, render work aside: 1 x 1-pixel tiles at
    1 sample rendered by the worker's own code in this process (no Dask), engines alternating by round;
    per engine the median over rounds of the median call."""
    from tracer_tools.farm import worker
    from tracer_tools.package import imported_beside

    if imported_beside(TRACER) is None:
        raise SystemExit(f"bench farm: no tracer package beside {TRACER}: run tools/bootstrap --python")
    jobs = {
        "process": worker.worker_job(
            "bench-process", [TRACER, SCENE, "--samples", "1", "--region-list", "--threads", "1", "-q"], ".ppm"
        ),
        "module": worker.module_job("bench-module", SCENE, {}, {"samples": "1", "encoding": "linear"}),
    }
    medians = {engine: [] for engine in ENGINES}
    for job in jobs.values():
        worker.start_job(job)
        worker.render_tile(job, "0 0 1 1")  # the scene loaded (or the process started) before timing
    for round_index in range(rounds):
        for engine in ENGINES if round_index % 2 == 0 else ENGINES[::-1]:
            times = []
            for _ in range(calls):
                start = time.perf_counter()
                worker.render_tile(jobs[engine], "0 0 1 1")
                times.append(time.perf_counter() - start)
            medians[engine].append(statistics.median(times))
    for job in jobs.values():
        worker.close_job(job["key"])
    return {engine: statistics.median(found) for engine, found in medians.items()}


def scheduler_cost(tasks: int = 400, rounds: int = 5) -> float:
    """Step 3a: seconds per task of Dask's scheduling alone (no-op tasks on tools/farm's local cluster)."""
    import logging

    from distributed import Client, LocalCluster

    with (
        LocalCluster(
            n_workers=2, threads_per_worker=1, processes=False, dashboard_address=None, silence_logs=logging.CRITICAL
        ) as cluster,
        Client(cluster) as client,
    ):
        times = []
        for _ in range(rounds):
            start = time.perf_counter()
            client.gather(client.map(lambda value: value, range(tasks), pure=False))
            times.append(time.perf_counter() - start)
    return statistics.median(times) / tasks


def predict(measured: dict, cost: dict, per_task_s: float) -> list[dict]:
    """Step 3b: the image on N single-core workers, and an image of 60 times the work (one engine's
    figures)."""
    split = measured["split_of_median_pair"]
    work = split["tile_work_s"] - cost["per_tile_s"] * split["tiles"]  # the pixels' own work, one core
    fixed = split["process_s"] - split["tiles_s"]  # start-up, checking, writing, shut-down, on the client
    client_per_tile = per_task_s + split["assembly_s"] / split["tiles"]  # serial: scheduler and client
    transfer = split["tile_bytes"] / LINK_BYTES_PER_S
    rows = []
    for workers in (1, 4, 16, 64):
        tiles = 16 * workers
        row = {"workers": workers, "tiles": tiles}
        for name, image_work in (("10s", work), ("10min", 60 * work)):
            spread = (image_work + cost["per_tile_s"] * tiles) / workers
            tail = image_work / tiles / 2  # half a tile of idling while the last tiles finish
            total = fixed + max(spread + tail, client_per_tile * tiles + transfer)
            row[f"seconds_{name}"] = total
            row[f"efficiency_{name}"] = image_work / total / workers
        rows.append(row)
    return rows


def report(data: dict) -> str:
    o, c = data["overhead"], data["per_tile"]
    lines = [
        f"# Render farm benchmark ({data['date']}, {data['machine']})",
        "",
        "Written by `tools/bench farm`; docs/farm.md discusses it. Two engines: **module**, the workers",
        "render in their own process with the tracer package (the default on a local cluster), and",
        "**process**, each worker drives a `tracer --region-list` process (the default with `--address`).",
        "",
        "## Overhead on a 10-second render (bunny_room, 1200 x 800, 121 samples per pixel)",
        "",
        "| round | tracer --threads 2 (s) | farm, process (s) | farm / tracer | farm, module (s) | farm / tracer |",
        "|---|---|---|---|---|---|",
    ]
    for number, row in enumerate(o["pairs"], 1):
        p, m = row["process"], row["module"]
        lines.append(
            f"| {number} | {row['tracer_s']:.2f} | {p['farm_s']:.2f} | {p['ratio']:.3f} | "
            f"{m['farm_s']:.2f} | {m['ratio']:.3f} |"
        )
    lines.append("")
    for engine in ENGINES:
        e = o[engine]
        same = "identical to tracer's in every round" if e["identical"] else "NOT identical to tracer's"
        lines.append(
            f"- {engine}: median ratio {e['median_ratio']:.3f}, the farm's overhead **"
            f"{100 * (e['median_ratio'] - 1):.1f}%**; images {same}."
        )
    ps, ms = o["process"]["split_of_median_pair"], o["module"]["split_of_median_pair"]
    rows = [
        ("whole process (Python start to exit)", "process_s", ".3f"),
        ("check of the scene by tracer (beside the next line)", "check_s", ".3f"),
        ("cluster start (imports of Dask included)", "cluster_start_s", ".3f"),
        ("tiles: first sent to last received", "tiles_s", ".3f"),
        ("tiles", "tiles", "d"),
        ("the tiles' work on the workers, summed", "tile_work_s", ".3f"),
        ("assembly on the client (decoding, pasting)", "assembly_s", ".3f"),
        ("writing the image", "write_s", ".3f"),
        ("shut-down (tracer processes or scenes, cluster)", "shutdown_s", ".3f"),
        ("bytes of tiles sent to the client", "tile_bytes", ","),
    ]
    lines += [
        "",
        "Where the farm's time went (each engine's median round; the check runs beside the cluster's start):",
        "",
        "| part | process | module |",
        "|---|---|---|",
    ]
    lines += [f"| {name} | {ps[key]:{form}} | {ms[key]:{form}} |" for name, key, form in rows]
    lines += [
        "",
        f"## Per-tile cost (the same scene at 16 samples per pixel, {data['sweeps']} sweeps, engines alternating)",
        "",
        "| tile side (px) | tiles | process: summed tile work (s) | module: summed tile work (s) |",
        "|---|---|---|---|",
    ]
    for p, m in zip(c["process"]["points"], c["module"]["points"], strict=True):
        lines.append(f"| {p['tile']} | {p['tiles']} | {p['tile_work_s']:.3f} | {m['tile_work_s']:.3f} |")
    identical = all(point["identical"] for engine in ENGINES for point in c[engine]["points"])
    per_process, per_module = c["process"]["per_tile_s"], c["module"]["per_tile_s"]
    lines += [
        "",
        "Least squares over every run: each tile adds "
        f"**{1e3 * per_process:.2f} ms** of work on a worker with tracer processes and "
        f"**{1e3 * per_module:.2f} ms** in process ({per_module / per_process:.2f}x; the image itself: "
        f"{c['process']['work_without_tiles_s']:.2f} s and {c['module']['work_without_tiles_s']:.2f} s). "
        "Assembly on the client per tile: "
        f"{1e3 * c['process']['assembly_per_tile_s']:.2f} ms (decoding a file) and "
        f"{1e3 * c['module']['assembly_per_tile_s']:.2f} ms (pasting an array). Every image "
        + ("identical to tracer's alone." if identical else "was NOT identical to tracer's alone."),
        "",
        f"Dask's scheduling, per task (no-op tasks on the local cluster): {1e3 * data['per_task_s']:.2f} ms.",
        "",
    ]
    if "fixed_per_task_s" in data:
        fixed = data["fixed_per_task_s"]
        whole = {engine: fixed[engine] + data["per_task_s"] for engine in ENGINES}
        lines += [
            "## A task's fixed cost (1 x 1-pixel tiles at 1 sample: render work aside)",
            "",
            "The workers' own code called in one process, engines alternating (medians of 5 rounds):",
            "",
            "| | process | module | module / process |",
            "|---|---|---|---|",
            f"| on the worker (ms) | {1e3 * fixed['process']:.3f} | {1e3 * fixed['module']:.3f} | "
            f"{fixed['module'] / fixed['process']:.2f}x |",
            f"| with Dask's scheduling (ms) | {1e3 * whole['process']:.3f} | {1e3 * whole['module']:.3f} | "
            f"{whole['module'] / whole['process']:.2f}x |",
            "",
        ]
    lines += [
        "## Predicted for N single-core workers (16 tiles per worker, the module engine)",
        "",
        "The 10-second image above, and one of 60 times its work (a 10-minute render on these 2 cores).",
        "Efficiency: one core's work on the image divided by (workers x predicted time).",
        "",
        "| workers | tiles | 10 s image: predicted s | efficiency | 10 min image: predicted s | efficiency |",
        "|---|---|---|---|---|---|",
    ]
    for row in data["prediction"]:
        lines.append(
            f"| {row['workers']} | {row['tiles']} | {row['seconds_10s']:.2f} | {100 * row['efficiency_10s']:.0f}% | "
            f"{row['seconds_10min']:.1f} | {100 * row['efficiency_10min']:.0f}% |"
        )
    return "\n".join(lines) + "\n"


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--quick", action="store_true", help="one pair, three tile sizes")
    parser.add_argument("--report-only", action="store_true", help="rewrite the report from the saved data")
    parser.add_argument("--pairs", type=option_types.whole_number(1, 1_000_000), default=5)
    parser.add_argument("--sweeps", type=option_types.whole_number(1, 1_000_000), default=2)
    arguments = parser.parse_args()
    model = next(
        (line.split(":", 1)[1].strip() for line in open("/proc/cpuinfo") if line.startswith("model name")), "?"
    )
    machine = f"{model}, {os.cpu_count()} cores"
    data_path = os.path.join(ROOT, "docs", "bench", "farm-bench.json")
    if arguments.report_only:
        with open(data_path) as file:
            data = json.load(file)
        data["prediction"] = predict(data["overhead"]["module"], data["per_tile"]["module"], data["per_task_s"])
        with open(os.path.join(ROOT, "docs", "bench", "farm-bench.md"), "w") as file:
            file.write(report(data))
        return 0
    with tempfile.TemporaryDirectory() as folder:
        measured = overhead(1 if arguments.quick else arguments.pairs, folder)
        sweeps = 1 if arguments.quick else arguments.sweeps
        cost = per_tile_cost([400, 100, 40] if arguments.quick else [400, 200, 100, 60, 40], sweeps, folder)
    per_task_s = scheduler_cost()
    fixed = fixed_cost(50 if arguments.quick else 200)
    data = {
        "date": datetime.date.today().isoformat(),
        "machine": machine,
        "sweeps": sweeps,
        "overhead": measured,
        "per_tile": cost,
        "per_task_s": per_task_s,
        "fixed_per_task_s": fixed,
        "prediction": predict(measured["module"], cost["module"], per_task_s),
    }
    with open(data_path, "w") as file:
        json.dump(data, file, indent=1)
    text = report(data)
    with open(os.path.join(ROOT, "docs", "bench", "farm-bench.md"), "w") as file:
        file.write(text)
    print(text)
    return 0


if __name__ == "__main__":
    sys.exit(main())
