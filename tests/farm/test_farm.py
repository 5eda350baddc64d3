"""tools/farm on a local cluster of 2 workers: images identical to tracer's own, faults survived."""

import json
import os
import signal
import socket
import subprocess
import sys
import time

import numpy as np
import psutil
import pytest
from conftest import ROOT, SCENES, farm, read_pixels, render

HERE = os.path.dirname(os.path.abspath(__file__))


@pytest.mark.parametrize("engine", ["module", "process"])
@pytest.mark.parametrize("extension", [".png", ".exr"])
@pytest.mark.parametrize("scene", ["task2", "bunny_room", "many_spheres"])
def test_tiled_render_is_identical_to_tracer_alone(tracer_bin, tmp_path, scene, extension, engine):
    alone = render(tracer_bin, SCENES / f"{scene}.scn", tmp_path / f"alone{extension}", "--width", "600")
    output = tmp_path / f"farm{extension}"
    timings = tmp_path / "timings.json"
    arguments = ["--width", 600, "--workers", 2, "--tile", 90, "--engine", engine, "--timings", timings]
    result = farm(SCENES / f"{scene}.scn", "-o", output, *arguments, tracer=tracer_bin)
    assert result.returncode == 0, result.stderr
    assert json.loads(timings.read_text())["engine"] == engine
    tiled, spec = read_pixels(output)
    assert tiled.dtype == alone.dtype and tiled.shape == alone.shape and tiled.shape[1] == 600
    assert np.array_equal(tiled, alone)
    assert [name for name in os.listdir(tmp_path) if name.startswith(".")] == []  # no temporary files left


def test_a_jittered_area_light_is_tiled_into_the_same_image(tracer_bin, tmp_path):
    """Jitter's random numbers come from each shaded point, not from the worker or the tile."""
    scene = tmp_path / "window.scn"
    text = (ROOT / "scenes" / "lights" / "window.scn").read_text()
    scene.write_text(text.replace("samples1 8 samples2 8 color 0.95", "samples1 5 samples2 5 color 0.95 jitter true"))
    alone = render(tracer_bin, scene, tmp_path / "alone.exr", "--width", "200")
    result = farm(scene, "-o", tmp_path / "farm.exr", "--width", 200, "--workers", 2, "--tile", 70, tracer=tracer_bin)
    assert result.returncode == 0, result.stderr
    tiled, _ = read_pixels(tmp_path / "farm.exr")
    assert np.array_equal(tiled, alone)


@pytest.mark.parametrize("engine", ["module", "process"])
def test_an_srgb_scene_is_tiled_into_the_same_srgb_file(tracer_bin, tmp_path, engine):
    scene = tmp_path / "srgb.scn"
    scene.write_text((SCENES / "task2.scn").read_text().replace("max_depth 4", "max_depth 4 encoding srgb"))
    alone = render(tracer_bin, scene, tmp_path / "alone.png", "--width", "300")
    arguments = ["--width", 300, "--workers", 2, "--tile", 90, "--engine", engine]
    result = farm(scene, "-o", tmp_path / "farm.png", *arguments, tracer=tracer_bin)
    assert result.returncode == 0, result.stderr
    tiled, _ = read_pixels(tmp_path / "farm.png")
    assert np.array_equal(tiled, alone)

    def chunks(path):  # the kinds of a PNG file's chunks, in order
        data, at, kinds = path.read_bytes(), 8, []
        while at < len(data):
            kinds.append(data[at + 4 : at + 8].decode())
            at += 12 + int.from_bytes(data[at : at + 4], "big")
        return kinds

    assert "sRGB" in chunks(tmp_path / "alone.png") and "sRGB" in chunks(tmp_path / "farm.png")


def test_jobs_file_renders_a_parameter_sweep(tracer_bin, tmp_path):
    jobs = [
        {"scene": str(SCENES / "chessboard.scn"), "output": f"ball{size}.png", "define": {"ball": size}, "width": 200}
        for size in (0.1, 0.3)
    ]
    (tmp_path / "jobs.json").write_text(json.dumps(jobs))
    result = farm("--jobs", tmp_path / "jobs.json", "--workers", 2, tracer=tracer_bin)
    assert result.returncode == 0, result.stderr
    for size in (0.1, 0.3):
        alone = render(
            tracer_bin, SCENES / "chessboard.scn", tmp_path / "alone.png", "--width", 200, "-D", f"ball={size}"
        )
        assert np.array_equal(read_pixels(tmp_path / f"ball{size}.png")[0], alone)
    assert not np.array_equal(read_pixels(tmp_path / "ball0.1.png")[0], read_pixels(tmp_path / "ball0.3.png")[0])


def test_nothing_of_dasks_own_reaches_stderr_when_its_port_is_taken(tracer_bin, tmp_path):
    # Dask's default HTTP port held (by this test, or by whatever holds it already, such as a
    # second farm): the farm must still say nothing of Dask's, no "Port 8787 is already in use".
    holder = socket.socket()
    holder.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
    try:
        holder.bind(("0.0.0.0", 8787))
        holder.listen()
    except OSError:
        pass  # in use already: the case itself
    try:
        result = farm(
            SCENES / "task2.scn", "-o", tmp_path / "t.png", "--width", 120, "--workers", 2, "-q", tracer=tracer_bin
        )
    finally:
        holder.close()
    assert result.returncode == 0, result.stderr
    assert result.stderr == ""


def flaky_farm(tracer_bin, tmp_path, failures, *arguments):
    """tools/farm on task2 at 300 px with a tracer whose first `failures` worker processes crash on their
    first tile (flaky_tracer.py, counting in tmp_path/state)."""
    env = {"REAL_TRACER": str(tracer_bin), "FLAKY_STATE": str(tmp_path / "state"), "FLAKY_FAILURES": str(failures)}
    return farm(
        SCENES / "task2.scn",
        *arguments,
        "--width",
        300,
        "--workers",
        2,
        tracer=os.path.join(HERE, "flaky_tracer.py"),
        env=env,
    )


def test_failed_tiles_are_retried(tracer_bin, tmp_path):
    alone = render(tracer_bin, SCENES / "task2.scn", tmp_path / "alone.png", "--width", 300)
    output = tmp_path / "farm.png"
    result = flaky_farm(tracer_bin, tmp_path, 2, "-o", output, "--tile", 100, "--retries", 2)
    assert result.returncode == 0, result.stderr
    assert (tmp_path / "state").read_text() == "xx"  # two tracer processes crashed
    assert np.array_equal(read_pixels(output)[0], alone)


def test_a_tile_that_keeps_failing_fails_the_job_with_tracers_diagnostic(tracer_bin, tmp_path):
    output = tmp_path / "farm.png"
    result = flaky_farm(tracer_bin, tmp_path, 1000, "-o", output, "--retries", 1)
    assert result.returncode == 1
    assert "failed 2 times; the last time:\ntracer: error: simulated crash" in result.stderr
    assert not output.exists() and os.listdir(tmp_path) == ["state"]


def test_the_module_engine_needs_the_package_beside_tracer(tmp_path):
    fake = tmp_path / "bin" / "tracer"  # an executable with no python/ folder beside it
    fake.parent.mkdir()
    fake.write_text("#!/bin/sh\nexit 1\n")
    fake.chmod(0o755)
    result = farm(SCENES / "task2.scn", "-o", tmp_path / "out.png", "--engine", "module", tracer=fake)
    assert result.returncode == 3, result.stderr
    assert result.stderr == (
        f"farm: error: --engine module: no tracer package built in '{fake.parent / 'python'}' "
        "(build it: tools/bootstrap --python)\n"
    )
    assert not (tmp_path / "out.png").exists()


def test_scene_error_is_reported_once_before_any_tile(tmp_path, tracer_bin):
    scene = tmp_path / "broken.scn"
    scene.write_text((SCENES / "task2.scn").read_text().replace("radius", "radios", 1))
    result = farm(scene, "-o", tmp_path / "out.png", "--workers", 2, tracer=tracer_bin)
    assert result.returncode == 1
    assert result.stderr.count("error: unknown key 'radios'") == 1, result.stderr
    assert result.stderr.startswith(f"{scene}:26:36: error: unknown key"), result.stderr  # tracer's own, as is
    assert "tile" not in result.stderr
    assert not (tmp_path / "out.png").exists()


def region_list_processes(root):
    """The tracer worker processes under the farm process `root`."""
    found = []
    for child in root.children(recursive=True):
        try:
            if "--region-list" in child.cmdline():
                found.append(child)
        except psutil.NoSuchProcess:
            pass
    return found


def wait_until(condition, failure, process=None, seconds=120):
    """Polls `condition` until it holds; fails with `failure` after `seconds` or if `process` ended."""
    deadline = time.monotonic() + seconds
    while not condition():
        assert time.monotonic() < deadline and (process is None or process.poll() is None), failure
        time.sleep(0.05)


def start_long_farm(output, tracer_bin, *extra):
    """A farm of many small tiles taking a few seconds, and its process (once tracer processes run, for a
    local cluster of the process engine; at once for the module engine's)."""
    command = [
        sys.executable,
        "-m",
        "tracer_tools.farm.farm",
        str(SCENES / "bunny_room.scn"),
        "-o",
        str(output),
        "--width",
        "600",
        "--samples",
        "36",
        "--tile",
        "40",
        "--tracer",
        str(tracer_bin),
        "-q",
        *extra,
    ]
    if "--address" not in extra:
        command += ["--workers", "2"]
    process = subprocess.Popen(
        command, env={**os.environ, "PYTHONPATH": str(ROOT / "tools")}, cwd=ROOT, stderr=subprocess.PIPE, text=True
    )
    root = psutil.Process(process.pid)
    if extra == ("--engine", "process"):
        wait_until(lambda: region_list_processes(root), "the farm started no worker", process)
    return process, root


def test_killed_tracer_mid_tile_still_gives_the_identical_image(tracer_bin, tmp_path):
    alone = render(tracer_bin, SCENES / "bunny_room.scn", tmp_path / "alone.png", "--width", 600, "--samples", 36)
    output = tmp_path / "farm.png"
    process, root = start_long_farm(output, tracer_bin, "--engine", "process")
    region_list_processes(root)[0].kill()  # a local worker's tracer process, loading or rendering
    assert not output.exists()  # killed mid-job
    _, errors = process.communicate(timeout=300)
    assert process.returncode == 0, errors
    assert np.array_equal(read_pixels(output)[0], alone)


@pytest.fixture
def dask_cluster(tmp_path):
    """A Dask scheduler and two single-thread workers (each a process under its nanny), as a cluster
    would run them; yields the scheduler's address and the process running the workers."""
    scheduler_file = tmp_path / "scheduler.json"

    def dask(*arguments):
        command = [os.path.join(os.path.dirname(sys.executable), "dask"), *arguments, "--scheduler-file"]
        command += [scheduler_file, "--no-dashboard", "--host", "127.0.0.1"]
        return subprocess.Popen(command, stderr=subprocess.DEVNULL, cwd=tmp_path)

    scheduler = dask("scheduler", "--port", "0")
    workers = dask("worker", "--nworkers", "2", "--nthreads", "1")

    def workers_started():
        return len([c for c in psutil.Process(workers.pid).children() if "python" in c.name()]) >= 2

    try:
        wait_until(workers_started, "the Dask workers did not start")
        address = json.loads(scheduler_file.read_text())["address"]
        yield address, psutil.Process(workers.pid)
    finally:
        for process in (workers, scheduler):
            process.terminate()
            process.wait(timeout=60)


def test_cluster_by_address_survives_a_killed_dask_worker(tracer_bin, tmp_path, dask_cluster):
    address, workers = dask_cluster
    alone = render(tracer_bin, SCENES / "bunny_room.scn", tmp_path / "alone.exr", "--width", 600, "--samples", 36)
    output = tmp_path / "farm.exr"
    process, _ = start_long_farm(output, tracer_bin, "--address", address)
    wait_until(lambda: region_list_processes(workers), "no tile reached the workers", process)
    region_list_processes(workers)[0].parent().kill()  # the Dask worker process (its nanny starts another)
    assert not output.exists()  # killed mid-job
    _, errors = process.communicate(timeout=300)
    assert process.returncode == 0, errors
    assert np.array_equal(read_pixels(output)[0], alone)


@pytest.mark.parametrize("engine", ["module", "process"])
def test_interrupted_farm_writes_nothing_and_leaves_no_tracer(tracer_bin, tmp_path, engine):
    output = tmp_path / "farm.png"
    process, root = start_long_farm(output, tracer_bin, "--engine", engine)
    kept = tmp_path / ".farm.png.farm"
    wait_until(lambda: kept.is_dir() and len(os.listdir(kept)) > 1, "no tile was kept", process)
    workers = region_list_processes(root)
    assert bool(workers) == (engine == "process")
    process.send_signal(signal.SIGINT)
    _, errors = process.communicate(timeout=120)
    assert process.returncode == 130, errors
    assert "interrupted" in errors
    assert set(os.listdir(tmp_path)) <= {".farm.png.farm"}  # finished tiles may be kept, no image
    psutil.wait_procs(workers, timeout=30)
    assert not any(worker.is_running() and worker.status() != psutil.STATUS_ZOMBIE for worker in workers)


def test_an_interrupted_job_run_again_renders_only_the_tiles_it_lacks(tracer_bin, tmp_path):
    alone = render(tracer_bin, SCENES / "bunny_room.scn", tmp_path / "alone.png", "--width", 600, "--samples", 36)
    output = tmp_path / "farm.png"
    kept = tmp_path / ".farm.png.farm"
    process, _ = start_long_farm(output, tracer_bin)

    def tiles_kept():
        return [name for name in os.listdir(kept) if name.startswith("tile-")] if kept.is_dir() else []

    wait_until(lambda: len(tiles_kept()) >= 4, "no tile was kept", process)
    process.send_signal(signal.SIGINT)
    _, errors = process.communicate(timeout=120)
    assert process.returncode == 130, errors
    assert "finished tiles are kept in" in errors and not output.exists()
    before = len(tiles_kept())
    assert (kept / "manifest.json").is_file() and before >= 4

    # The same command again: the kept tiles are pasted, only the others rendered.
    timings = tmp_path / "timings.json"
    command = [SCENES / "bunny_room.scn", "-o", output, "--width", 600, "--samples", 36, "--tile", 40]
    result = farm(*command, "--workers", 2, "-q", "--timings", timings, tracer=tracer_bin)
    assert result.returncode == 0, result.stderr
    figures = json.loads(timings.read_text())
    assert figures["tiles_kept"] == before
    assert figures["tiles"] + before == 15 * 10  # 600 x 400 in tiles of 40
    assert np.array_equal(read_pixels(output)[0], alone)
    assert not kept.exists()
