"""What runs on the workers, by the job's engine. "process": tracer processes (one per job and worker
thread) that load the scene once and render the job's tiles one after another (`tracer
--region-list`), each tile returned as the bytes of its image file. "module": the scene loaded once per
worker process by the tracer package (tracer.load) and each tile rendered in the worker's own thread
into an array (float32, or the bytes of an 8-bit file), returned as it is. Standard library, Dask
and the tracer package only: tools/farm uploads this file to a cluster's workers, which need Dask
and the tracer executable (or the package), not this folder."""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
import tempfile
import threading
import time
import types


def worker_job(key: str, command: list[str], tile_suffix: str) -> dict:
    """How a worker runs tracer processes for one job: `key` names one job of one farm run, `command`
    loads its scene (tracer SCENE [overrides] --region-list ...), tiles come back as `tile_suffix`
    files (".ppm" for 8-bit outputs: raw bytes, quick to read; ".exr" for float ones; both lossless).
    Plain data: the workers need no module of this folder to read it."""
    return {"key": key, "engine": "process", "command": list(command), "tile_suffix": tile_suffix}


def module_job(key: str, scene: str, defines: dict, settings: dict) -> dict:
    """How a worker renders one job with the tracer package: `scene` loaded with `defines` (-D), each
    tile rendered with `settings` (Scene.render's keywords: samples, width, ..., encoding)."""
    return {"key": key, "engine": "module", "scene": scene, "defines": dict(defines), "settings": dict(settings)}


def _processes() -> types.ModuleType:
    """This worker process's tracer processes: `every[key]` all of a job's, `idle[key]` those waiting
    for a tile. Kept in sys.modules so that every task sent by value finds the same table."""
    holder = sys.modules.get("_tracer_farm_processes")
    if holder is None:
        holder = types.ModuleType("_tracer_farm_processes")
        holder.every, holder.idle = {}, {}
        holder.scenes = {}  # the module engine's: key -> {"lock", "scene", "stopped": its renders' stop}
        holder.closed = set()  # the keys of jobs closed here
        holder.ahead = {}  # (key, first, last) -> (process, folder): runs of frames asked for ahead
        holder.lock = threading.Lock()
        sys.modules["_tracer_farm_processes"] = holder
    return holder


def _start(job: dict) -> subprocess.Popen:
    """A new tracer process of the job (it loads the scene, then waits for regions)."""
    errors = tempfile.TemporaryFile()
    process = subprocess.Popen(
        job["command"], stdin=subprocess.PIPE, stdout=subprocess.PIPE, stderr=errors, text=True, bufsize=1
    )
    process.errors = errors
    holder = _processes()
    with holder.lock:
        holder.every.setdefault(job["key"], []).append(process)
    return process


def _take(job: dict) -> subprocess.Popen:
    """An idle tracer process of the job that is still running, or a new one."""
    holder = _processes()
    with holder.lock:
        idle = holder.idle.setdefault(job["key"], [])
        while idle:
            process = idle.pop()
            if process.poll() is None:
                return process
    return _start(job)


def _give_back(job: dict, process: subprocess.Popen) -> None:
    holder = _processes()
    with holder.lock:
        holder.idle.setdefault(job["key"], []).append(process)


def _scene(job: dict) -> tuple[object, threading.Event]:
    """The module engine's scene of the job, loaded on first use by one thread (the others wait), and
    the event that stops its renders."""
    holder = _processes()
    with holder.lock:
        if job["key"] in holder.closed:
            raise RuntimeError("the job was closed on this worker")
        entry = holder.scenes.setdefault(
            job["key"], {"lock": threading.Lock(), "scene": None, "stopped": threading.Event()}
        )
    with entry["lock"]:
        if entry["scene"] is None:
            import tracer

            try:
                entry["scene"] = tracer.load(job["scene"], defines=job["defines"])
            except tracer.SceneError as error:
                raise RuntimeError(str(error)) from None
        return entry["scene"], entry["stopped"]


def start_job(job: dict, dask_worker: object = None) -> int:
    """Starts one tracer process per thread of this worker (Dask's client.run gives the worker) ahead of
    the job's tiles, so that loading the scene overlaps the farm's own start; with the module engine,
    one thread that loads the scene. How many it started."""
    if job["engine"] == "module":
        threading.Thread(target=_load_quietly, args=(job,), daemon=True).start()
        return 1
    count = dask_worker.state.nthreads if dask_worker is not None else 1
    for _ in range(count):
        _give_back(job, _start(job))
    return count


def _load_quietly(job: dict) -> None:
    """_scene, ahead of the tiles: a failure is the first tile's to report (it loads again)."""
    try:
        _scene(job)
    except Exception:
        with _processes().lock:
            _processes().scenes.pop(job["key"], None)


def _diagnostic(process: subprocess.Popen) -> str:
    """What a tracer process that stopped said on stderr."""
    process.wait()
    process.errors.seek(0)
    text = process.errors.read().decode(errors="replace").strip()
    return text or f"tracer stopped with exit code {process.returncode} and no message"


def _scratch_folder() -> str | None:
    """The Dask worker's own scratch folder (its nanny removes it if the worker dies mid-tile), or
    the system's temporary folder outside a worker."""
    try:
        from distributed import get_worker

        return get_worker().local_directory
    except (ImportError, ValueError):
        return None


def _send(process: subprocess.Popen, request: str) -> bool:
    """Sends one request line to a kept tracer process; False if the process is gone."""
    try:
        process.stdin.write(request + "\n")
        process.stdin.flush()
        return True
    except (BrokenPipeError, OSError, ValueError):
        return False


def _reply(process: subprocess.Popen) -> str:
    """A kept tracer process's reply line to its request ("" if the process is gone: its stderr
    then says why)."""
    try:
        return process.stdout.readline()
    except (OSError, ValueError):
        return ""


def _ask(process: subprocess.Popen, request: str) -> str:
    """Sends one request line to a kept tracer process and returns its reply line."""
    return _reply(process) if _send(process, request) else ""


def render_tile(job: dict, region_text: str) -> tuple[object, float]:
    """Renders one tile ("X0 Y0 W H"): its image file's bytes (the module engine: its pixels, height x
    width x 3) and the seconds it took here."""
    start = time.perf_counter()
    if job["engine"] == "module":
        scene, stopped = _scene(job)
        region = tuple(int(field) for field in region_text.split())
        pixels = scene.render(region=region, threads=1, stop=stopped.is_set, **job["settings"])
        return pixels, time.perf_counter() - start
    process = _take(job)
    with tempfile.TemporaryDirectory(prefix="tracer-tile-", dir=_scratch_folder()) as folder:
        path = os.path.join(folder, "tile" + job["tile_suffix"])
        reply = _ask(process, f"{region_text} {path}")
        if not reply:
            raise RuntimeError(_diagnostic(process))
        _give_back(job, process)
        if not reply.startswith("done "):
            raise RuntimeError("tracer: " + reply.strip())
        with open(path, "rb") as tile:
            return tile.read(), time.perf_counter() - start


def close_job(key: str, at_once: bool = False) -> int:
    """Ends this worker's tracer processes of a job: their input closes and they exit, or with `at_once`
    they are stopped in the middle of a tile (tracer writes nothing then); the module engine's scene is
    let go (and with `at_once` its renders stopped). How many processes (or scenes) there were."""
    holder = _processes()
    with holder.lock:
        processes = holder.every.pop(key, [])
        holder.idle.pop(key, None)
        scene = holder.scenes.pop(key, None)
        ahead = [holder.ahead.pop(run) for run in list(holder.ahead) if run[0] == key]
        holder.closed.add(key)
    if scene is not None and at_once:
        scene["stopped"].set()  # renders under way stop within 20 ms (RenderStopped)
    for process in processes:
        try:
            if at_once:
                process.terminate()
            process.stdin.close()
            process.wait(timeout=30)
        except (OSError, subprocess.TimeoutExpired):
            process.kill()
    for _, folder in ahead:
        shutil.rmtree(folder, ignore_errors=True)
    return len(processes) + (scene is not None)


def _frames_request(first: int, last: int, folder: str, suffix: str) -> str:
    """The --frame-list request line for frames `first` to `last`, written into `folder`."""
    return f"{first} {last} {os.path.join(folder, 'frame_#######' + suffix)}"


def ask_ahead(job: dict, first: int, last: int) -> None:
    """Asks one of this process's tracer processes of the job for frames `first` to `last` before
    their task comes (a local cluster's workers are threads of this process: the farm asks while
    Dask starts); render_frames of that run then waits for this reply instead of asking."""
    process = _take(job)
    folder = tempfile.mkdtemp(prefix="tracer-frames-")
    holder = _processes()
    with holder.lock:
        holder.ahead[(job["key"], first, last)] = (process, folder)
    _send(process, _frames_request(first, last, folder, job["tile_suffix"]))  # if it fails, the task says so


def render_frames(job: dict, first: int, last: int) -> tuple[list[tuple[int, bytes]], float]:
    """Renders frames `first` to `last` of an animation with one of this worker's tracer processes of
    the job (`tracer SCENE [options] --frames N ... --frame-list`: the scene compiled and its meshes
    built once per process, for every run it is sent): each frame's number and file bytes (the job's
    tile_suffix is the frames' extension), and the seconds it took here."""
    start = time.perf_counter()
    holder = _processes()
    with holder.lock:
        ahead = holder.ahead.pop((job["key"], first, last), None)
    if ahead is not None:  # asked for already (ask_ahead)
        process, folder = ahead
        reply = _reply(process)
    else:
        process = _take(job)
        folder = tempfile.mkdtemp(prefix="tracer-frames-", dir=_scratch_folder())
        reply = _ask(process, _frames_request(first, last, folder, job["tile_suffix"]))
    try:
        if not reply.startswith("done "):
            if reply.startswith("error: "):  # a request it refused: the process is still good
                _give_back(job, process)
                raise RuntimeError("tracer: " + reply.strip())
            raise RuntimeError(_diagnostic(process))
        _give_back(job, process)
        frames = []
        for frame in range(first, last + 1):
            with open(os.path.join(folder, f"frame_{frame:07d}{job['tile_suffix']}"), "rb") as file:
                frames.append((frame, file.read()))
        return frames, time.perf_counter() - start
    finally:
        shutil.rmtree(folder, ignore_errors=True)
