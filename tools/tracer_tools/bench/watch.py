"""How soon a saved change shows: tracer --watch on a copy of a scene (default scenes/task2.scn),
saved again and again as an editor saves (a new file renamed over the old, a sphere's radius
changed each time); for each save, the time until the preview and until the full image are on
disk (tracer reports each image after writing it). Output as committed in docs/bench/bench-watch.txt.

    tools/bench watch [--scene scenes/task2.scn] [--saves 21] [--threads N]
"""

import argparse
import json
import os
import pathlib
import queue
import shutil
import signal
import statistics
import subprocess
import tempfile
import threading
import time

from tracer_tools import ROOT, option_types
from tracer_tools.bench.common import TRACER, git, machine


def events_of(process: subprocess.Popen, events: queue.Queue) -> None:
    for line in process.stdout:
        events.put((time.perf_counter(), json.loads(line)))


def wait_for(events: queue.Queue, kind: str, stage: str | None = None) -> tuple[float, dict]:
    while True:
        at, event = events.get(timeout=60)
        if event["event"] == "load" and not event["ok"] or event["event"] == "error":
            raise SystemExit(f"tools/bench watch: tracer: {event.get('text') or event.get('message')}")
        if event["event"] == kind and (stage is None or event.get("stage") == stage):
            return at, event


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--scene", type=option_types.existing_path, default=ROOT / "scenes" / "task2.scn")
    parser.add_argument("--saves", type=option_types.whole_number(1, 1_000_000), default=21)
    parser.add_argument("--threads", type=option_types.whole_number(0, 4096), default=os.cpu_count())
    args = parser.parse_args()
    print(f"# tools/bench watch: {time.strftime('%Y-%m-%d')}, {git('rev-parse', '--short', 'HEAD')}")
    print(f"# machine: {machine()}; threads used: {args.threads}; release preset (-O3 -march=native)")
    text = args.scene.read_text()
    if "radius" not in text:
        parser.error(f"{args.scene} has no 'radius' for the benchmark to change")
    with tempfile.TemporaryDirectory() as folder:
        scene = pathlib.Path(folder) / args.scene.name
        shutil.copy(args.scene, scene)
        for other in args.scene.parent.glob("*"):  # what it includes or reads
            if other != args.scene and not (pathlib.Path(folder) / other.name).exists():
                os.symlink(other.resolve(), pathlib.Path(folder) / other.name)
        output = pathlib.Path(folder) / "out.png"
        process = subprocess.Popen(
            [
                str(TRACER),
                str(scene),
                "-o",
                str(output),
                "--watch",
                "--diagnostics",
                "json",
                "--threads",
                str(args.threads),
            ],
            stdout=subprocess.PIPE,
            text=True,
        )
        events: queue.Queue = queue.Queue()
        threading.Thread(target=events_of, args=(process, events), daemon=True).start()
        wait_for(events, "image", "full")
        previews, fulls = [], []
        for i in range(args.saves):
            time.sleep(0.3)
            changed = text.replace("radius", f"radius {0.001 * (i + 1):.3f} +", 1)
            temporary = scene.with_name(scene.name + ".new")
            temporary.write_text(changed)
            saved = time.perf_counter()
            os.replace(temporary, scene)
            preview_at, preview = wait_for(events, "image")
            full_at, full = (preview_at, preview) if preview["stage"] == "full" else wait_for(events, "image", "full")
            previews.append((preview_at - saved) * 1000)
            fulls.append((full_at - saved) * 1000)
            print(
                f"  save {i + 1:2}: preview {previews[-1]:6.1f} ms ({preview['width']}x{preview['height']}), "
                f"full {fulls[-1]:6.1f} ms ({full['width']}x{full['height']})",
                flush=True,
            )
        process.send_signal(signal.SIGINT)
        process.wait(timeout=30)
    for name, values, target in (("preview", previews, 300), ("full image", fulls, 1000)):
        print(
            f"{name}: median {statistics.median(values):.1f} ms, max {max(values):.1f} ms after the save "
            f"(target {target} ms) over {len(values)} saves"
        )
    return 0
