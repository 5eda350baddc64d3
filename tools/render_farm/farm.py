"""tools/farm: renders one scene split into tiles, or a list of jobs, with tracer on a Dask cluster
(a local one on this machine's cores unless --address names a scheduler), and writes each image
atomically once all its tiles are in. Every pixel is the one `tracer` alone would give.

    tools/farm scenes/task2.scn -o out.png
    tools/farm scenes/bunny_room.scn -o poster.exr --samples 16 --width 4800
    tools/farm --jobs sweep.json --address tcp://scheduler:8786
"""

from __future__ import annotations

import argparse
import json
import logging
import os
import signal
import sys
import time

import numpy as np

from render_farm import worker
from render_farm.images import decode_tile, write_atomically
from render_farm.jobs import OVERRIDES, Job, JobError, check_job, check_output, jobs_from_file
from render_farm.progress import Progress
from render_farm.tiles import Canvas, Region, split, tile_size_for

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
EXIT_INTERRUPTED = 130


def parse_arguments(argv: list[str]) -> argparse.Namespace:
    parser = argparse.ArgumentParser(
        prog="tools/farm", description=__doc__.split("\n\n")[0], formatter_class=argparse.RawTextHelpFormatter
    )
    parser.add_argument("scene", nargs="?", help="the scene file (.scn)")
    parser.add_argument("-o", "--output", help="the image to write (.png, .exr, ...)")
    parser.add_argument("--jobs", help='a JSON list of jobs: {"scene", "output", "define", ' + ", ".join(OVERRIDES))
    parser.add_argument("-D", "--define", action="append", default=[], help="NAME=VALUE, as tracer's -D")
    for key in OVERRIDES:
        parser.add_argument("--" + key.replace("_", "-"), help=f"override the scene's {key}, as tracer's option")
    parser.add_argument("--tile", type=int, help="tile side in pixels (default: about 4 tiles per worker)")
    parser.add_argument("--workers", type=int, default=os.cpu_count(), help="local cluster's workers (default: cores)")
    parser.add_argument("--address", help="join this Dask scheduler (tcp://host:8786) instead of a local cluster")
    parser.add_argument("--retries", type=int, default=2, help="times a failed tile is tried again (default 2)")
    default_tracer = os.path.join(ROOT, "build", "release", "tracer")
    parser.add_argument("--tracer", default=default_tracer, help="the tracer executable (default: this build's)")
    parser.add_argument("--worker-tracer", help="tracer's path on the workers (default: --tracer's)")
    parser.add_argument("--timings", help="write the time split (start-up, tiles, assembly) as JSON here")
    parser.add_argument("-q", "--quiet", action="store_true", help="no progress line")
    arguments = parser.parse_args(argv)
    if bool(arguments.jobs) == bool(arguments.scene):
        parser.error("give one scene (with -o) or --jobs FILE")
    if arguments.scene and not arguments.output:
        parser.error("no output image given (-o out.png)")
    if arguments.jobs and (arguments.output or arguments.define or any(getattr(arguments, k) for k in OVERRIDES)):
        parser.error("--jobs gives each job's output and settings; -o, -D and overrides are for one scene")
    if arguments.retries < 0 or arguments.workers < 1 or (arguments.tile is not None and arguments.tile < 1):
        parser.error("--retries must be 0 or more, --workers and --tile 1 or more")
    return arguments


def jobs_of(arguments: argparse.Namespace) -> list[Job]:
    """The jobs to run, checked by tracer (each scene error reported once, before any tile is sent)."""
    if arguments.jobs:
        jobs = jobs_from_file(arguments.jobs)
    else:
        if arguments.scene == "-":
            raise JobError("the farm needs a scene file; standard input cannot be sent to workers", 2)
        defines = {}
        for text in arguments.define:
            name, equals, value = text.partition("=")
            if not equals or not name:
                raise JobError(f"-D {text}: expected NAME=VALUE, e.g. -D radius=0.3", 2)
            defines[name] = value
        overrides = {key: getattr(arguments, key) for key in OVERRIDES if getattr(arguments, key) is not None}
        jobs = [Job(os.path.abspath(arguments.scene), os.path.abspath(arguments.output), defines, overrides)]
    if not os.access(arguments.tracer, os.X_OK):
        raise JobError(f"no tracer executable at '{arguments.tracer}' (build it: tools/bootstrap)", 3)
    for job in jobs:
        warnings = check_job(arguments.tracer, job)
        if warnings:
            sys.stderr.write(warnings)
        check_output(job)
    return jobs


def start_cluster(arguments: argparse.Namespace):
    """A Dask client on the scheduler named, or on a new local cluster of one single-thread worker per core;
    a worker that dies counts against the tile's retries."""
    import dask
    from distributed import Client, LocalCluster

    dask.config.set({"distributed.scheduler.allowed-failures": arguments.retries})
    if arguments.address:
        return Client(arguments.address, timeout="30s"), None
    cluster = LocalCluster(
        n_workers=arguments.workers,
        threads_per_worker=1,
        processes=True,
        dashboard_address=None,
        silence_logs=logging.CRITICAL,
    )
    return Client(cluster), cluster


def tile_failure(job: Job, region: Region, error: BaseException, retries: int) -> str:
    """The message for a tile that failed on every try: tracer's own diagnostic where there is one."""
    tries = f"{retries + 1} time{'s' if retries else ''}"
    if type(error).__name__ == "KilledWorker":
        reason = "the workers running it died"
    else:
        reason = str(error) or type(error).__name__
    return f"tile {region.text()} of {job.scene} failed {tries}; the last time:\n{reason}"


def run_jobs(arguments: argparse.Namespace, jobs: list[Job], timings: dict) -> None:
    """Sends every tile of every job, pastes them as they come back and writes each finished image."""
    import cloudpickle
    from distributed import as_completed

    cloudpickle.register_pickle_by_value(worker)  # the workers need Dask and tracer, not this folder
    start = time.perf_counter()
    client, cluster = start_cluster(arguments)
    timings["cluster_start_s"] = time.perf_counter() - start
    slots = sum(client.nthreads().values()) or arguments.workers
    worker_tracer = arguments.worker_tracer or os.path.abspath(arguments.tracer)
    keys = [job.key(index) for index, job in enumerate(jobs)]
    try:
        # Step 1: every tile of every job, in order.
        start = time.perf_counter()
        pending, canvases = {}, []
        for index, job in enumerate(jobs):
            tile = arguments.tile or tile_size_for(job.width, job.height, slots)
            regions = split(job.width, job.height, tile)
            suffix = ".exr" if job.is_float() else ".png"
            command = (worker_tracer, *job.tracer_arguments(), "--region-list", "--threads", "1", "-q")
            worker_job = worker.WorkerJob(keys[index], command, suffix)
            canvases.append(Canvas(job.width, job.height, np.float32 if job.is_float() else np.uint8, len(regions)))
            for number, region in enumerate(regions):
                future = client.submit(
                    worker.render_tile,
                    worker_job,
                    region.text(),
                    retries=arguments.retries,
                    pure=False,
                    key=f"{keys[index]}-tile-{number}",
                )
                pending[future] = (index, region, suffix)

        # Step 2: tiles pasted as they arrive; each image written when complete.
        progress = Progress(len(pending), quiet=arguments.quiet)
        assembly = writing = work = 0.0
        for future in as_completed(list(pending)):
            index, region, suffix = pending[future]
            if future.status != "finished":
                raise JobError(tile_failure(jobs[index], region, future.exception(), arguments.retries), 1)
            data, seconds = future.result()
            work += seconds
            moment = time.perf_counter()
            canvas = canvases[index]
            canvas.paste(region, decode_tile(data, suffix, canvas.pixels.dtype))
            assembly += time.perf_counter() - moment
            if canvas.complete():
                moment = time.perf_counter()
                write_atomically(jobs[index].output, canvas.pixels)
                writing += time.perf_counter() - moment
                canvases[index] = None
            progress.tile_done()
        progress.finish()
        timings.update(
            tiles=len(pending),
            workers=slots,
            tiles_s=time.perf_counter() - start,
            tile_work_s=work,
            assembly_s=assembly,
            write_s=writing,
        )
    finally:
        start = time.perf_counter()
        for future in pending:
            future.cancel()
        for key in keys:
            try:
                client.run(worker.close_job, key)
            except Exception:  # a worker that is gone has nothing to close
                pass
        client.close()
        if cluster is not None:
            cluster.close()
        timings["shutdown_s"] = time.perf_counter() - start


def main(argv: list[str] | None = None) -> int:
    arguments = parse_arguments(sys.argv[1:] if argv is None else argv)
    # SIGTERM stops the farm as Ctrl-C does: nothing unfinished is written.
    signal.signal(signal.SIGTERM, signal.default_int_handler)
    timings: dict = {}
    start = time.perf_counter()
    try:
        jobs = jobs_of(arguments)
        timings["check_s"] = time.perf_counter() - start
        run_jobs(arguments, jobs, timings)
    except JobError as error:
        print(f"farm: error: {error}" if not str(error).startswith("tracer") else str(error), file=sys.stderr)
        return error.exit_code
    except KeyboardInterrupt:
        print("farm: interrupted; no unfinished image was written", file=sys.stderr)
        return EXIT_INTERRUPTED
    timings["total_s"] = time.perf_counter() - start
    if arguments.timings:
        with open(arguments.timings, "w", encoding="utf-8") as file:
            json.dump({key: round(value, 4) for key, value in timings.items()}, file, indent=2)
    return 0


if __name__ == "__main__":
    sys.exit(main())
