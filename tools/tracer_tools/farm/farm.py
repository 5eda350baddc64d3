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
import tempfile
import time
import zipfile
from concurrent.futures import Future, ThreadPoolExecutor
from typing import TYPE_CHECKING, NoReturn

import tracer_tools
from tracer_tools import option_types
from tracer_tools.farm import frames, worker
from tracer_tools.farm.jobs import OVERRIDES, Job, JobError, OutputChecks, check_job, jobs_from_file
from tracer_tools.farm.progress import Progress
from tracer_tools.package import folder_beside, imported_beside

if TYPE_CHECKING:
    from distributed import Client, LocalCluster

    from tracer_tools.farm.tiles import Region

# Images' modules (NumPy, OpenImageIO: 0.1 to 0.2 s to import) are imported by the tiles' path
# alone (run_jobs, check_jobs): an animation's frames come back as tracer's own files.

ROOT = str(tracer_tools.ROOT)
EXIT_INTERRUPTED = 130


# Set by Ctrl-C or SIGTERM. The handler also raises KeyboardInterrupt, but Python swallows an
# exception raised inside a garbage-collector or weakref callback (Dask installs some): the flag
# is what every image write and the exit status consult, so such an interrupt is never lost.
INTERRUPTED = {"signal": False}


def on_interrupt(number: int, frame: object) -> None:
    INTERRUPTED["signal"] = True
    raise KeyboardInterrupt


def parse_arguments(argv: list[str]) -> argparse.Namespace:
    parser = argparse.ArgumentParser(
        prog="tools/farm", description=__doc__.split("\n\n")[0], formatter_class=argparse.RawTextHelpFormatter
    )
    parser.add_argument("scene", type=option_types.existing_file, nargs="?", help="the scene file (.scn)")
    parser.add_argument("-o", "--output", type=option_types.output_file, help="the image to write (.png, .exr, ...)")
    parser.add_argument(
        "--jobs",
        type=option_types.existing_file,
        help='a JSON list of jobs: {"scene", "output", "define", ' + ", ".join(OVERRIDES),
    )
    parser.add_argument(
        "-D", "--define", type=option_types.free_text, action="append", default=[], help="NAME=VALUE, as tracer's -D"
    )
    for key in OVERRIDES:  # checked by tracer itself, before any tile
        parser.add_argument(
            "--" + key.replace("_", "-"),
            type=option_types.free_text,
            help=f"override the scene's {key}, as tracer's option",
        )
    parser.add_argument(
        "--tile",
        type=option_types.whole_number(1, 16384),
        help="tile side in pixels (default: about 16 tiles per worker)",
    )
    parser.add_argument(
        "--workers",
        type=option_types.whole_number(1, 1_000_000),
        default=os.cpu_count(),
        help="local cluster's workers (default: cores)",
    )
    parser.add_argument(
        "--address",
        type=option_types.free_text,
        help="join this Dask scheduler (tcp://host:8786) instead of a local cluster",
    )
    parser.add_argument(
        "--connect-timeout",
        type=option_types.real_number(0, low_open=True),
        default=30,
        help="seconds to wait for --address's scheduler (default 30)",
    )
    parser.add_argument(
        "--retries",
        type=option_types.whole_number(0, 100),
        default=2,
        help="times a failed tile is tried again (default 2)",
    )
    default_tracer = os.path.join(ROOT, "build", "release", "tracer")
    parser.add_argument(
        "--tracer",
        type=option_types.executable_file,
        default=default_tracer,
        help="the tracer executable (default: this build's)",
    )
    parser.add_argument(
        "--worker-tracer", type=option_types.free_text, help="tracer's path on the workers (default: --tracer's)"
    )
    parser.add_argument(
        "--engine",
        choices=("auto", "module", "process"),
        default="auto",
        help="how workers render: 'module' in their own process with the tracer package beside --tracer\n"
        "(its python/ folder), 'process' with tracer processes; 'auto' (default): module on a local\n"
        "cluster when that package is built, else process",
    )
    parser.add_argument(
        "--timings", type=option_types.output_file, help="write the time split (start-up, tiles, assembly) as JSON here"
    )
    parser.add_argument("-q", "--quiet", action="store_true", help="no progress line")
    add_frame_options(parser)
    arguments = parser.parse_args(argv)
    if bool(arguments.jobs) == bool(arguments.scene):
        parser.error("give one scene (with -o) or --jobs FILE")
    if arguments.scene and not arguments.output:
        parser.error("no output image given (-o out.png)")
    if arguments.jobs and (arguments.output or arguments.define or any(getattr(arguments, k) for k in OVERRIDES)):
        parser.error("--jobs gives each job's output and settings; -o, -D and overrides are for one scene")
    animated = arguments.clock is not None or arguments.cyclic or arguments.subset is not None or arguments.resume
    if arguments.frames is None and (animated or arguments.frames_per_task is not None):
        parser.error(
            "--clock, --cyclic, --subset, --resume and --frames-per-task are for an animation: give --frames N"
        )
    if arguments.frames is not None and arguments.jobs:
        parser.error("--frames renders one scene's animation; --jobs lists images")
    if arguments.retries < 0 or arguments.workers < 1 or (arguments.tile is not None and arguments.tile < 1):
        parser.error("--retries must be 0 or more, --workers and --tile 1 or more")
    return arguments


def add_frame_options(parser: argparse.ArgumentParser) -> None:
    """The animation's options: tracer's, and how many frames one task renders."""
    parser.add_argument(
        "--frames",
        type=option_types.whole_number(1, 1_000_000),
        help="render an animation of N frames (tracer's --frames) into -o's numbered names; frames are the tasks",
    )
    parser.add_argument("--clock", type=option_types.free_text, help="FIRST:LAST, as tracer's --clock")
    parser.add_argument("--cyclic", action="store_true", help="as tracer's --cyclic")
    parser.add_argument("--subset", type=option_types.free_text, help="FIRST[:LAST], as tracer's --subset")
    parser.add_argument("--resume", action="store_true", help="keep the frames already there and whole")
    parser.add_argument(
        "--frames-per-task",
        type=option_types.whole_number(1, 1_000_000),
        help="consecutive frames one task renders (default: about 3 tasks per worker)",
    )


def jobs_of(arguments: argparse.Namespace) -> list[Job]:
    """The jobs to run, as the command line or the jobs file gives them (not checked yet)."""
    if arguments.jobs:
        return jobs_from_file(arguments.jobs)
    if arguments.scene == "-":
        raise JobError("the farm needs a scene file; standard input cannot be sent to workers", 2)
    defines = {}
    for text in arguments.define:
        name, equals, value = text.partition("=")
        if not equals or not name:
            raise JobError(f"-D {text}: expected NAME=VALUE, e.g. -D radius=0.3", 2)
        defines[name] = value
    overrides = {key: getattr(arguments, key) for key in OVERRIDES if getattr(arguments, key) is not None}
    return [Job(os.path.abspath(arguments.scene), os.path.abspath(arguments.output), defines, overrides)]


def choose_engine(arguments: argparse.Namespace) -> tuple[str, str]:
    """How the workers render ("module" or "process", by --engine) and the file that renders (the
    package's extension, or the tracer executable)."""
    if arguments.engine == "process" or (arguments.engine == "auto" and arguments.address):
        return "process", arguments.tracer
    package = imported_beside(arguments.tracer)
    if package is not None:
        return "module", os.path.abspath(package._tracer.__file__)
    if arguments.engine == "module":
        folder = folder_beside(arguments.tracer)
        raise JobError(
            f"--engine module: no tracer package built in '{folder}' (build it: tools/bootstrap --python)", 3
        )
    return "process", arguments.tracer


def check_jobs(tracer: str, jobs: list[Job], engine: str = "process", renderer: str | None = None) -> None:
    """Checks every job's scene with tracer and its output path (each scene error is reported once, by
    the JobError raised, before any tile is sent); prints tracer's warnings. `engine` and `renderer`
    (choose_engine's) go into each job's manifest."""
    if not os.access(tracer, os.X_OK):
        raise JobError(f"no tracer executable at '{tracer}' (build it: tools/bootstrap)", 3)
    # Each distinct scene (tracer's arguments) is checked and its inputs hashed once; each output
    # folder and format checked once: 10^5 jobs of one scene plan in seconds.
    from tracer_tools.farm import resume

    checked = {}  # tracer's arguments -> (the checked job, the inputs' digests)
    outputs = OutputChecks()
    renderer = renderer or tracer
    tracer_digest = resume.file_digest(renderer)
    for job in jobs:
        key = tuple(job.tracer_arguments())
        if key in checked:
            first, inputs = checked[key]
            job.width, job.height, job.inputs = first.width, first.height, first.inputs
        else:
            warnings = check_job(tracer, job)
            if warnings:
                sys.stderr.write(warnings)
            try:
                inputs = resume.input_digests(job)
            except OSError as error:  # an input that vanished since the check
                raise JobError(f"cannot read '{error.filename}': {error.strerror}", 3) from error
            checked[key] = job, inputs
        outputs.check(job)
        job.manifest = resume.identity(renderer, job, inputs, tracer_digest, engine)


def start_cluster(arguments: argparse.Namespace) -> tuple[Client, LocalCluster | None]:
    """A Dask client on the scheduler named, or on a local cluster of one single-thread worker per core.
    Local workers are threads of this process: each only drives its own tracer process, which does the
    work, so separate worker processes would add their start-up (0.35 to 0.7 s measured) and nothing else.
    A worker that dies counts against the tile's retries."""
    import dask
    from distributed import Client, LocalCluster

    dask.config.set({"distributed.scheduler.allowed-failures": arguments.retries})
    if arguments.address:
        try:
            return Client(arguments.address, timeout=f"{arguments.connect_timeout}s"), None
        except (OSError, ValueError, TimeoutError) as error:
            raise JobError(f"cannot reach the Dask scheduler at '{arguments.address}': {error}", 3) from error
    # No dashboard; the scheduler's HTTP server (which Dask starts even so, for its health and
    # metrics routes) on a free port: on its default, 8787, a second farm on the machine printed
    # Dask's "Port 8787 is already in use" warning before anything of tracer's.
    cluster = LocalCluster(
        n_workers=arguments.workers,
        threads_per_worker=1,
        processes=False,
        dashboard_address=None,
        scheduler_kwargs={"dashboard_address": "127.0.0.1:0"},
        silence_logs=logging.CRITICAL,
    )
    return Client(cluster), cluster


def send_worker_module(client: Client) -> None:
    """Uploads tracer_tools.farm.worker (the tasks' code: standard library and Dask only) to the cluster's
    scheduler and workers, which then need Dask and the tracer executable, not this folder."""
    package = os.path.dirname(os.path.abspath(worker.__file__))
    tools = os.path.dirname(package)
    with tempfile.TemporaryDirectory(prefix="tracer-farm-") as folder:
        archive = os.path.join(folder, "tracer_render_farm_worker.zip")
        with zipfile.ZipFile(archive, "w") as zipped:
            zipped.write(os.path.join(tools, "__init__.py"), "tracer_tools/__init__.py")
            for name in ("__init__.py", "worker.py"):
                zipped.write(os.path.join(package, name), f"tracer_tools/farm/{name}")
        client.upload_file(archive)


def tile_failure(job: Job, region: Region, error: BaseException, retries: int) -> str:
    """The message for a tile that failed on every try: tracer's own diagnostic where there is one."""
    tries = f"{retries + 1} time{'s' if retries else ''}"
    if type(error).__name__ == "KilledWorker":
        reason = "the workers running it died"
    else:
        reason = str(error) or type(error).__name__
    return f"tile {region.text()} of {job.scene} failed {tries}; the last time:\n{reason}"


def worker_job_of(arguments: argparse.Namespace, engine: str, job: Job, key: str) -> dict:
    """What the workers are sent of `job` for the engine chosen."""
    if engine == "module":
        settings = {name: str(value) for name, value in job.overrides.items()}
        encoding = None if job.is_float() else "srgb" if job.srgb else "linear"
        return worker.module_job(key, job.scene, job.defines, {**settings, "encoding": encoding})
    worker_tracer = arguments.worker_tracer or os.path.abspath(arguments.tracer)
    return worker.worker_job(
        key,
        [worker_tracer, *job.tracer_arguments(), "--region-list", "--threads", "1", "-q"],
        ".exr" if job.is_float() else ".ppm",
    )


def run_jobs(
    arguments: argparse.Namespace, jobs: list[Job], checking: Future, timings: dict, engine: str = "process"
) -> None:
    """Starts the cluster and the workers' tracer processes of the first job while the jobs are checked
    (`checking`: no tile is sent before every scene passed), sends every tile of every job, pastes them as
    they come back and writes each finished image."""
    start = time.perf_counter()
    import numpy as np
    from distributed import as_completed

    from tracer_tools.farm import resume
    from tracer_tools.farm.images import decode_tile, write_atomically
    from tracer_tools.farm.tiles import Canvas, split, tile_size_for

    client, cluster = start_cluster(arguments)
    if arguments.address:
        send_worker_module(client)
    timings["cluster_start_s"] = time.perf_counter() - start
    keys = [job.key(index) for index, job in enumerate(jobs)]
    worker_jobs = [worker_job_of(arguments, engine, job, keys[index]) for index, job in enumerate(jobs)]
    pending = {}
    try:
        client.run(worker.start_job, worker_jobs[0])  # the first scene loads on the workers meanwhile
        checking.result()
        slots = sum(client.nthreads().values()) or arguments.workers

        # Step 1: every tile of every job, in order, but those an earlier run of the job kept.
        start = time.perf_counter()
        canvases, stores = [], []
        kept_tiles = 0
        written = []  # the jobs whose image is written, in order
        for index, job in enumerate(jobs):
            stores.append(resume.TileStore(job.output, job.manifest))
            tile, kept = stores[index].resume(arguments.tile, tile_size_for(job.width, job.height, slots))
            regions = split(job.width, job.height, tile)
            worker_job = worker_jobs[index]
            suffix = worker_job.get("tile_suffix")  # None: the pixels as an array, not a file
            canvases.append(Canvas(job.width, job.height, np.float32 if job.is_float() else np.uint8, len(regions)))
            for region in regions:
                if region in kept:
                    canvases[index].paste(region, kept[region])
                    kept_tiles += 1
            if canvases[index].complete():  # every tile kept: only the writing was left
                write_atomically(job.output, canvases[index].pixels, job.srgb)
                written.append(index)
                stores[index].remove()
                canvases[index] = None
            for number, region in enumerate(regions):
                if region in kept:
                    continue
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
        transferred = 0
        for future in as_completed(list(pending)):
            index, region, suffix = pending[future]
            if future.status != "finished":
                raise JobError(tile_failure(jobs[index], region, future.exception(), arguments.retries), 1)
            data, seconds = future.result()
            work += seconds
            transferred += data.nbytes if suffix is None else len(data)
            moment = time.perf_counter()
            canvas = canvases[index]
            pixels = data if suffix is None else decode_tile(data, suffix, canvas.pixels.dtype)
            canvas.paste(region, pixels)
            assembly += time.perf_counter() - moment
            if INTERRUPTED["signal"]:  # an interrupt that a callback swallowed: stop at this tile
                raise KeyboardInterrupt
            moment = time.perf_counter()
            if canvas.complete():
                write_atomically(jobs[index].output, canvas.pixels, jobs[index].srgb)
                written.append(index)
                stores[index].remove()
                canvases[index] = None
            else:
                stores[index].keep(region, pixels)
            writing += time.perf_counter() - moment
            progress.tile_done()
        progress.finish()
        if not arguments.quiet:
            seconds = time.perf_counter() - timings["started"]
            for index in written:
                job = jobs[index]
                print(f"farm: wrote {job.output}: {job.width}x{job.height}, {seconds:.2f} s", file=sys.stderr)
        timings.update(
            tiles=len(pending),
            tiles_kept=kept_tiles,
            workers=slots,
            tiles_s=time.perf_counter() - start,
            tile_work_s=work,
            tile_bytes=transferred,
            assembly_s=assembly,
            write_s=writing,
        )
    finally:
        # Step 3: the workers' tracer processes end (at once if the job stopped early), then the cluster.
        start = time.perf_counter()
        stopped_early = not pending or any(not future.done() for future in pending)
        for future in pending:
            future.cancel()
        for key in keys:
            try:
                client.run(worker.close_job, key, stopped_early)
            except Exception:  # a worker that is gone has nothing to close
                pass
        client.close()
        if cluster is not None:
            cluster.close()
        timings["shutdown_s"] = time.perf_counter() - start


def tile_folder(job: Job) -> str:
    """Where the finished tiles of `job` are kept for --resume (resume.folder_of)."""
    from tracer_tools.farm import resume

    return resume.folder_of(job.output)


def main(argv: list[str] | None = None) -> int:
    arguments = parse_arguments(sys.argv[1:] if argv is None else argv)
    # SIGTERM stops the farm as Ctrl-C does: nothing unfinished is written.
    signal.signal(signal.SIGINT, on_interrupt)
    signal.signal(signal.SIGTERM, on_interrupt)
    start = time.perf_counter()
    timings: dict = {"started": start}

    engine, renderer = "process", arguments.tracer

    def check(jobs: list[Job]) -> None:
        check_jobs(arguments.tracer, jobs, engine, renderer)
        timings["check_s"] = time.perf_counter() - start

    jobs: list[Job] = []
    failed = None  # the exit code of a failure
    try:
        jobs = jobs_of(arguments)
        if arguments.frames is None:  # an animation's frames are rendered by tracer processes
            engine, renderer = choose_engine(arguments)
        timings["engine"] = engine
        if arguments.frames is not None:
            frames.run_animation(arguments, jobs[0], start_cluster, timings, INTERRUPTED)
            jobs = []  # no tiles are kept for frames: each is written whole
        else:
            with ThreadPoolExecutor(1) as pool:
                run_jobs(arguments, jobs, pool.submit(check, jobs), timings, engine)
    except JobError as error:
        print(str(error) if error.tracers_own else f"farm: error: {error}", file=sys.stderr)
        failed = error.exit_code
    except OSError as error:  # writing an image: disk full, permissions changed meanwhile
        print(f"farm: error: {error}", file=sys.stderr)
        failed = 3
    except KeyboardInterrupt:
        INTERRUPTED["signal"] = True
    kept = (
        [] if arguments.frames is not None else [folder for folder in map(tile_folder, jobs) if os.path.isdir(folder)]
    )
    if kept:
        others = " and beside the other outputs" if len(kept) > 1 else ""
        print(
            f"farm: finished tiles are kept in {kept[0]}{others}; the same command again renders only the rest",
            file=sys.stderr,
        )
    if failed is not None:
        return failed
    if INTERRUPTED["signal"]:
        print("farm: interrupted; no unfinished image was written", file=sys.stderr)
        return EXIT_INTERRUPTED
    timings["total_s"] = time.perf_counter() - start
    if arguments.timings:
        with open(arguments.timings, "w", encoding="utf-8") as file:
            figures = {key: value for key, value in timings.items() if key != "started"}
            rounded = {key: round(value, 4) if isinstance(value, float) else value for key, value in figures.items()}
            json.dump(rounded, file, indent=2)
    return 0


def command() -> NoReturn:
    """tools/farm: main(), then the process ends at once. Everything is written and closed by then;
    Python's own teardown of Dask's modules and threads would add 0.07 s to every run."""
    code = main()
    sys.stdout.flush()
    sys.stderr.flush()
    logging.shutdown()
    os._exit(code)


if __name__ == "__main__":
    command()
