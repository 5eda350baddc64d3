"""What runs on the workers: one tracer process per job and worker thread, which loads the scene once
and renders the job's tiles one after another (`tracer --region-list`), each tile returned as the bytes
of its image file. Sent to the workers by value, so they need Dask and the tracer executable only."""

from __future__ import annotations

import os
import subprocess
import sys
import tempfile
import threading
import time
import types
from dataclasses import dataclass


@dataclass(frozen=True)
class WorkerJob:
    """How a worker runs tracer for one job: the command that loads the scene and the tile format."""

    key: str  # one job of one farm run
    command: tuple[str, ...]  # tracer SCENE [overrides] --region-list --threads 1 -q
    tile_suffix: str  # ".png" for 8-bit outputs, ".exr" for float outputs (both lossless)


class TileFailed(Exception):
    """A tile tracer could not render: the tracer's own diagnostic."""


def _processes() -> dict:
    """This worker process's tracer processes, by (job key, thread): kept in sys.modules so that every
    task sent by value finds the same table."""
    holder = sys.modules.get("_tracer_farm_processes")
    if holder is None:
        holder = types.ModuleType("_tracer_farm_processes")
        holder.table = {}
        holder.lock = threading.Lock()
        sys.modules["_tracer_farm_processes"] = holder
    return holder


def _tracer_for(job: WorkerJob) -> subprocess.Popen:
    """The running tracer process of this job and thread, started if missing or dead."""
    holder = _processes()
    slot = (job.key, threading.get_ident())
    with holder.lock:
        process = holder.table.get(slot)
        if process is None or process.poll() is not None:
            errors = tempfile.TemporaryFile()
            process = subprocess.Popen(
                job.command, stdin=subprocess.PIPE, stdout=subprocess.PIPE, stderr=errors, text=True, bufsize=1
            )
            process.errors = errors
            holder.table[slot] = process
    return process


def _diagnostic(process: subprocess.Popen) -> str:
    """What a tracer process that stopped said on stderr."""
    process.wait()
    process.errors.seek(0)
    text = process.errors.read().decode(errors="replace").strip()
    return text or f"tracer stopped with exit code {process.returncode} and no message"


def render_tile(job: WorkerJob, region_text: str) -> tuple[bytes, float]:
    """Renders one tile ("X0 Y0 W H"): its image file's bytes and the seconds it took here."""
    start = time.perf_counter()
    process = _tracer_for(job)
    with tempfile.TemporaryDirectory(prefix="tracer-tile-") as folder:
        path = os.path.join(folder, "tile" + job.tile_suffix)
        try:
            process.stdin.write(f"{region_text} {path}\n")
            process.stdin.flush()
            reply = process.stdout.readline()
        except (BrokenPipeError, OSError):
            reply = ""
        if not reply:
            raise TileFailed(_diagnostic(process))
        if not reply.startswith("done "):
            raise TileFailed("tracer: " + reply.strip())
        with open(path, "rb") as tile:
            return tile.read(), time.perf_counter() - start


def close_job(key: str) -> int:
    """Ends this worker's tracer processes of a job (their input closes; they exit). How many there were."""
    holder = _processes()
    with holder.lock:
        slots = [slot for slot in holder.table if slot[0] == key]
        for slot in slots:
            process = holder.table.pop(slot)
            try:
                process.stdin.close()
                process.wait(timeout=10)
            except (OSError, subprocess.TimeoutExpired):
                process.kill()
    return len(slots)
