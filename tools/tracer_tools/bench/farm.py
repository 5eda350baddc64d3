"""The render farm's overhead and scaling, measured on this machine. Writes docs/bench/farm-bench.json and
docs/bench/farm-bench.md; docs/farm.md discusses them.

    tools/bench farm            # about 4 minutes on 2 cores
    tools/bench farm --quick    # one pair and a short sweep, for a try

1. Overhead: `tracer --threads 2` and the farm (a local cluster of 2 workers) render the same
   10-second image (bunny_room, 121 samples per pixel) one after the other, PAIRS times; each is timed
   as a whole process (start to exit, as a user waits for it); the overhead is the median of the
   per-pair ratios farm / tracer, minus one. The farm's own timings (--timings) split its time.
2. Per-tile cost: the farm renders a 1.5-second image (16 samples) at tile sizes from 400 to 40
   pixels; the tiles' summed work on the workers grows by a fixed cost per tile (least squares).
3. Prediction for N workers (one core each) on a cluster, from the measured parts: start-up,
   writing and shut-down, the work spread over N, the per-tile cost of 16 tiles per worker, half a
   tile of idling at the end, unless the serial part is longer: Dask's scheduling of each tile
   (measured with no-op tasks), pasting on the client and the tiles' bytes at 1 Gbit/s.
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


def farm_command(output: str, timings: str, *extra) -> list[str]:
    return [sys.executable, "-m", "tracer_tools.farm.farm", SCENE, "-o", output, "-q", "--timings", timings, *extra]


def overhead(pairs: int, folder: str) -> dict:
    """Step 1: tracer alone against the farm, alternating."""
    env = {**os.environ, "PYTHONPATH": os.path.join(ROOT, "tools")}
    timings_path = os.path.join(folder, "timings.json")
    rows = []
    for _ in range(pairs):
        alone = wall(
            [TRACER, SCENE, "-o", os.path.join(folder, "alone.png"), "-q", "--threads", "2", "--samples", "121"]
        )
        farm = wall(
            farm_command(os.path.join(folder, "farm.png"), timings_path, "--samples", "121", "--workers", "2"), env
        )
        with open(timings_path) as file:
            rows.append({"tracer_s": alone, "farm_s": farm, "ratio": farm / alone, "timings": json.load(file)})
    middle = sorted(rows, key=lambda row: row["ratio"])[len(rows) // 2]
    return {
        "pairs": rows,
        "median_ratio": statistics.median(row["ratio"] for row in rows),
        "median_tracer_s": statistics.median(row["tracer_s"] for row in rows),
        "median_farm_s": statistics.median(row["farm_s"] for row in rows),
        "split_of_median_pair": middle["timings"] | {"process_s": middle["farm_s"]},
    }


def per_tile_cost(tiles: list[int], folder: str) -> dict:
    """Step 2: the tiles' summed work against their number."""
    env = {**os.environ, "PYTHONPATH": os.path.join(ROOT, "tools")}
    timings_path = os.path.join(folder, "timings.json")
    points = []
    for tile in tiles:
        extra = ["--samples", "16", "--workers", "2", "--tile", str(tile)]
        wall(farm_command(os.path.join(folder, "sweep.png"), timings_path, *extra), env)
        with open(timings_path) as file:
            timings = json.load(file)
        points.append(
            {"tile": tile, **{key: timings[key] for key in ("tiles", "tile_work_s", "tiles_s", "tile_bytes")}}
        )
    xs = [point["tiles"] for point in points]
    ys = [point["tile_work_s"] for point in points]
    mean_x, mean_y = statistics.mean(xs), statistics.mean(ys)
    slope = sum((x - mean_x) * (y - mean_y) for x, y in zip(xs, ys, strict=True)) / sum((x - mean_x) ** 2 for x in xs)
    return {"points": points, "per_tile_s": slope, "work_without_tiles_s": mean_y - slope * mean_x}


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
    """Step 3b: the image on N single-core workers, and an image of 60 times the work."""
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
    s = o["split_of_median_pair"]
    lines = [
        f"# Render farm benchmark ({data['date']}, {data['machine']})",
        "",
        "Written by `tools/bench farm`; docs/farm.md discusses it.",
        "",
        "## Overhead on a 10-second render (bunny_room, 1200 x 800, 121 samples per pixel)",
        "",
        "| pair | tracer --threads 2 (s) | farm, 2 local workers (s) | farm / tracer |",
        "|---|---|---|---|",
    ]
    for number, row in enumerate(o["pairs"], 1):
        lines.append(f"| {number} | {row['tracer_s']:.2f} | {row['farm_s']:.2f} | {row['ratio']:.3f} |")
    lines += [
        "",
        f"Median ratio {o['median_ratio']:.3f}: the farm's overhead is **{100 * (o['median_ratio'] - 1):.1f}%**.",
        "",
        "Where the farm's time went (the median pair; the check runs beside the cluster's start):",
        "",
        "| part | seconds |",
        "|---|---|",
        f"| whole process (Python start to exit) | {s['process_s']:.3f} |",
        f"| check of the scene by tracer (beside the next line) | {s['check_s']:.3f} |",
        f"| cluster start (imports of Dask included) | {s['cluster_start_s']:.3f} |",
        f"| tiles: first sent to last received ({s['tiles']} tiles) | {s['tiles_s']:.3f} |",
        f"| the tiles' work on the workers, summed | {s['tile_work_s']:.3f} |",
        f"| assembly on the client (decoding, pasting) | {s['assembly_s']:.3f} |",
        f"| writing the image | {s['write_s']:.3f} |",
        f"| shut-down (tracer processes, cluster) | {s['shutdown_s']:.3f} |",
        f"| bytes of tiles sent to the client | {s['tile_bytes']:,} |",
        "",
        "## Per-tile cost (the same scene at 16 samples per pixel)",
        "",
        "| tile side (px) | tiles | summed tile work (s) | first sent to last received (s) |",
        "|---|---|---|---|",
    ]
    for point in c["points"]:
        lines.append(f"| {point['tile']} | {point['tiles']} | {point['tile_work_s']:.3f} | {point['tiles_s']:.3f} |")
    lines += [
        "",
        f"Least squares: each tile adds {1e3 * c['per_tile_s']:.2f} ms of work on a worker "
        f"(the image itself: {c['work_without_tiles_s']:.2f} s).",
        "",
        f"Dask's scheduling, per task (no-op tasks on the local cluster): {1e3 * data['per_task_s']:.2f} ms.",
        "",
        "## Predicted for N single-core workers (16 tiles per worker)",
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
    arguments = parser.parse_args()
    model = next(
        (line.split(":", 1)[1].strip() for line in open("/proc/cpuinfo") if line.startswith("model name")), "?"
    )
    machine = f"{model}, {os.cpu_count()} cores"
    data_path = os.path.join(ROOT, "docs", "bench", "farm-bench.json")
    if arguments.report_only:
        with open(data_path) as file:
            data = json.load(file)
        data["prediction"] = predict(data["overhead"], data["per_tile"], data["per_task_s"])
        with open(os.path.join(ROOT, "docs", "bench", "farm-bench.md"), "w") as file:
            file.write(report(data))
        return 0
    with tempfile.TemporaryDirectory() as folder:
        measured = overhead(1 if arguments.quick else arguments.pairs, folder)
        cost = per_tile_cost([400, 100, 40] if arguments.quick else [400, 200, 100, 60, 40], folder)
    data = {
        "date": datetime.date.today().isoformat(),
        "machine": machine,
        "overhead": measured,
        "per_tile": cost,
        "prediction": predict(measured, cost),
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
