"""The frames of an animation on the farm: runs of consecutive frames are its tasks (one frame each
by default), rendered on each worker by a tracer process that stays (`tracer --frames N
--frame-list`: the scene compiled and its meshes built once per worker, as the tiles' `--region-list`
processes load a scene once), the frames' files sent back and written here atomically, each the file
`tracer --frames N` alone writes, byte for byte. With --resume, frames already there and whole are
kept, as tracer's own --resume keeps them."""

from __future__ import annotations

import argparse
import os
import re
import struct
import sys
import tempfile
import time
from concurrent.futures import ThreadPoolExecutor, wait
from typing import Callable

from tracer_tools.farm import worker
from tracer_tools.farm.jobs import Job, JobError, OutputChecks, check_job
from tracer_tools.farm.progress import Progress

# The animation options passed on to tracer, as the farm's command line names them.
FRAME_OPTIONS = ("frames", "clock", "cyclic", "subset")
_NUMBER_FIELD = re.compile(r"#+")


def frame_path(pattern: str, frame: int) -> str:
    """`pattern` with its file name's last run of '#' replaced by the frame number, zero-padded to the
    run's length: tracer's rule (app/frames.h)."""
    folder, name = os.path.split(pattern)
    runs = list(_NUMBER_FIELD.finditer(name))
    if not runs:
        return pattern
    run = runs[-1]
    return os.path.join(folder, name[: run.start()] + str(frame).zfill(len(run.group())) + name[run.end() :])


def whole_frame(path: str, width: int, height: int) -> bool:
    """True if `path` holds a whole image of that size, by tracer's rule for --resume: a PNG whose
    header says the size and that ends with IEND, a PPM with every byte, any other file not empty."""
    try:
        size = os.path.getsize(path)
        with open(path, "rb") as file:
            head = file.read(64)
            file.seek(max(size - 12, 0))
            tail = file.read(12)
    except OSError:
        return False
    extension = os.path.splitext(path)[1].lower()
    if extension == ".ppm":
        header = f"P6\n{width} {height}\n255\n".encode()
        return head.startswith(header) and size == len(header) + 3 * width * height
    if extension == ".png":
        return (
            head.startswith(b"\x89PNG\r\n\x1a\n")
            and len(head) >= 24
            and struct.unpack(">II", head[16:24]) == (width, height)
            and tail == b"\x00\x00\x00\x00IEND\xaeB`\x82"
        )
    return size > 0


def frame_range(arguments: argparse.Namespace) -> tuple[int, int]:
    """The first and last frame the command line asks for (both made)."""
    if arguments.subset is None:
        return 0, arguments.frames - 1
    first, _, last = arguments.subset.partition(":")
    return int(first), int(last or first)


def tasks_of(frames: list[int], per_task: int) -> list[tuple[int, int]]:
    """Runs of consecutive frames, each of at most `per_task` frames."""
    tasks: list[tuple[int, int]] = []
    for frame in frames:
        if tasks and tasks[-1][1] == frame - 1 and frame - tasks[-1][0] < per_task:
            tasks[-1] = (tasks[-1][0], frame)
        else:
            tasks.append((frame, frame))
    return tasks


def animation_options(arguments: argparse.Namespace) -> list[str]:
    """The animation as tracer's options (without --subset: each task gives its own)."""
    options = ["--frames", str(arguments.frames)]
    if arguments.clock is not None:
        options += ["--clock", arguments.clock]
    if arguments.cyclic:
        options.append("--cyclic")
    return options


def write_frame(path: str, data: bytes) -> None:
    """The frame's file written beside `path` under a temporary name, then renamed over it."""
    folder, name = os.path.split(path)
    handle, temporary = tempfile.mkstemp(prefix=f".{name}.", dir=folder)
    try:
        with os.fdopen(handle, "wb") as file:
            file.write(data)
            file.flush()
            os.fsync(file.fileno())
        os.chmod(temporary, 0o644)
        os.replace(temporary, path)
    except BaseException:
        if os.path.exists(temporary):
            os.unlink(temporary)
        raise


def check_pattern(job: Job, arguments: argparse.Namespace) -> None:
    """Raises JobError if the output names one file for several frames."""
    if not _NUMBER_FIELD.search(os.path.basename(job.output)) and arguments.subset is None:
        raise JobError(
            f"-o '{job.output}' names one file for {arguments.frames} frames: put a number field in its file "
            "name, e.g. frame_####.png (#### becomes 0000, 0001, ...)",
            2,
        )


def check_animation(tracer: str, job: Job, arguments: argparse.Namespace) -> tuple[list[int], list[int]]:
    """Checks every frame with tracer (raising JobError with its diagnostics) and the output, and gives
    the job its frame size. The frames kept (--resume: whole already) and those to render."""
    warnings = check_job(tracer, job, ("--subset", arguments.subset) if arguments.subset is not None else ())
    if warnings:
        sys.stderr.write(warnings)
    first, last = frame_range(arguments)
    OutputChecks().check(Job(job.scene, frame_path(job.output, first)))
    frames = range(first, last + 1)
    kept = [f for f in frames if arguments.resume and whole_frame(frame_path(job.output, f), job.width, job.height)]
    kept_set = set(kept)
    return kept, [f for f in frames if f not in kept_set]


def check_and_ask_ahead(
    tracer: str, job: Job, arguments: argparse.Namespace, frames_job: dict | None
) -> tuple[list[int], list[int]]:
    """check_animation, then (given a local cluster's `frames_job`) the first task of each worker asked
    of its tracer process already."""
    kept, wanted = check_animation(tracer, job, arguments)
    if frames_job is not None:
        for first, last in tasks_of(wanted, arguments.frames_per_task or 1)[: arguments.workers]:
            worker.ask_ahead(frames_job, first, last)
    return kept, wanted


def run_animation(
    arguments: argparse.Namespace, job: Job, start_cluster: Callable, timings: dict, interrupted: dict
) -> None:
    """Renders the animation's frames on the cluster, writing each as it comes back. The frames are
    checked while Dask is imported and the cluster starts (half a second of Python's), and the
    workers' tracer processes load the scene meanwhile; no frame is sent before the check passed. On a
    local cluster the workers' first frames are asked for then, rendering while Dask starts: on 2
    cores, Dask's import (0.35-0.5 s of one core) then shares them with the frames instead of
    coming before every frame."""
    check_pattern(job, arguments)
    job.animation = animation_options(arguments)
    tracer = arguments.worker_tracer or os.path.abspath(arguments.tracer)
    key = job.key(0)
    command = [tracer, *job.tracer_arguments(), "--frame-list", "--threads", "1", "-q"]
    frames_job = worker.worker_job(key, command, os.path.splitext(job.output)[1])
    local = not arguments.address  # the workers are threads of this process (start_cluster)
    client = cluster = None
    futures: dict = {}
    checking = None
    with ThreadPoolExecutor(1) as pool:
        try:
            if local:  # their tracer processes start now and load the scene while Dask is imported
                for _ in range(arguments.workers):
                    worker.start_job(frames_job)
            checking = pool.submit(check_and_ask_ahead, arguments.tracer, job, arguments, frames_job if local else None)
            start = time.perf_counter()  # Dask is imported here
            client, cluster = start_cluster(arguments)
            timings["cluster_start_s"] = time.perf_counter() - start
            if not local:
                client.run(worker.start_job, frames_job)  # each worker's tracer loads the scene meanwhile
            kept, wanted = checking.result()
            timings["check_s"] = time.perf_counter() - timings["started"]
            render_frames(arguments, job, client, frames_job, (kept, wanted), futures, timings, interrupted)
        finally:
            if checking is not None:
                wait([checking])  # it asks no process once this job's are closed
            stopped_early = any(not future.done() for future in futures)
            for future in futures:
                future.cancel()
            if local:  # how many tracer processes it took: one a worker unless one failed
                timings["worker_processes"] = worker.close_job(key, stopped_early or not futures)
            elif client is not None:
                try:
                    client.run(worker.close_job, key, stopped_early)
                except Exception:  # a worker that is gone has nothing to close
                    pass
            if client is not None:
                client.close()
            if cluster is not None:
                cluster.close()


def render_frames(
    arguments: argparse.Namespace,
    job: Job,
    client: object,
    frames_job: dict,
    plan: tuple[list[int], list[int]],
    futures: dict,
    timings: dict,
    interrupted: dict,
) -> None:
    """Sends every frame of `plan` (kept, wanted) not kept, in tasks of --frames-per-task, and writes each
    as it comes back."""
    from distributed import as_completed

    kept, wanted = plan
    slots = sum(client.nthreads().values()) or arguments.workers
    per_task = arguments.frames_per_task or 1
    start = time.perf_counter()
    for task_first, task_last in tasks_of(wanted, per_task):
        future = client.submit(
            worker.render_frames, frames_job, task_first, task_last, retries=arguments.retries, pure=False
        )
        futures[future] = (task_first, task_last)
    progress = Progress(len(wanted), quiet=arguments.quiet, unit="frames")
    work = 0.0
    for future in as_completed(list(futures)):
        task_first, task_last = futures[future]
        if future.status != "finished":
            error = future.exception()
            reason = "the workers running it died" if type(error).__name__ == "KilledWorker" else str(error)
            raise JobError(f"frames {task_first} to {task_last} failed {arguments.retries + 1} times:\n{reason}", 1)
        rendered, seconds = future.result()
        work += seconds
        for frame, data in rendered:
            write_frame(frame_path(job.output, frame), data)
        if interrupted["signal"]:
            raise KeyboardInterrupt
        progress.tile_done(len(rendered))
    progress.finish()
    if not arguments.quiet:
        print(
            f"farm: wrote {len(wanted)} frames ({len(kept)} kept) of {job.width}x{job.height}, "
            f"{time.perf_counter() - timings['started']:.2f} s",
            file=sys.stderr,
        )
    timings.update(
        frames=len(wanted),
        frames_kept=len(kept),
        tasks=len(futures),
        workers=slots,
        frames_s=time.perf_counter() - start,
        frame_work_s=work,
    )
