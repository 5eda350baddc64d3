"""tools/farm --frames on a local cluster of 2 workers: the frames are the tasks, each file the one
`tracer --frames` writes alone, byte for byte; resumed runs keep whole frames; bad animations refused."""

import json
import os
import subprocess
import tempfile

import pytest
from conftest import SCENES, farm

from tracer_tools.farm import worker

# bunny_room with a zoom: every frame differs.
ANIMATED = (SCENES / "bunny_room.scn").read_text().replace("fovy 45", "fovy 40 + 20 * clock", 1)


@pytest.fixture
def scene(tmp_path):
    path = tmp_path / "zoom.scn"
    path.write_text(ANIMATED.replace('"meshes/', f'"{SCENES}/meshes/'))
    return path


def alone(tracer_bin, scene, folder, *options):
    """The frames tracer writes in one process: their bytes by frame number."""
    folder.mkdir()
    command = [tracer_bin, scene, "-q", "--width", "64", "--frames", "7", *options, "-o", folder / "f_##.png"]
    subprocess.run(list(map(str, command)), check=True)
    return {int(path.stem[2:]): path.read_bytes() for path in folder.iterdir()}


@pytest.mark.parametrize("options", [[], ["--cyclic", "--clock", "1:-1"]])
def test_farm_frames_are_tracers_own_byte_for_byte(tracer_bin, tmp_path, scene, options):
    expected = alone(tracer_bin, scene, tmp_path / "alone", *options)
    assert len(expected) == 7 and len(set(expected.values())) == 7  # the camera zooms: every frame differs
    result = farm(
        scene,
        "-o",
        tmp_path / "f_##.png",
        "--width",
        64,
        "--frames",
        7,
        *options,
        "--workers",
        2,
        "--frames-per-task",
        2,
        tracer=tracer_bin,
    )
    assert result.returncode == 0, result.stderr
    for frame, data in expected.items():
        assert (tmp_path / f"f_{frame:02d}.png").read_bytes() == data, frame
    assert [p.name for p in tmp_path.iterdir() if p.name.startswith(".")] == []  # no temporary files


def test_a_resumed_farm_keeps_whole_frames_and_makes_the_rest(tracer_bin, tmp_path, scene):
    expected = alone(tracer_bin, scene, tmp_path / "alone")
    for frame in (0, 2, 3, 6):
        (tmp_path / f"f_{frame:02d}.png").write_bytes(expected[frame])
    (tmp_path / "f_03.png").write_bytes(expected[3][:100])  # cut short: made again
    timings = tmp_path / "timings.json"
    result = farm(
        scene,
        "-o",
        tmp_path / "f_##.png",
        "--width",
        64,
        "--frames",
        7,
        "--resume",
        "--workers",
        2,
        "--timings",
        timings,
        tracer=tracer_bin,
    )
    assert result.returncode == 0, result.stderr
    assert "4 frames (3 kept)" in result.stderr
    for frame, data in expected.items():
        assert (tmp_path / f"f_{frame:02d}.png").read_bytes() == data, frame
    # The frames asked for while Dask started were wanted ones (1 and 3): no third process was needed.
    assert json.loads(timings.read_text())["worker_processes"] == 2


def test_frames_asked_for_ahead_are_the_tasks_own_and_unclaimed_ones_are_cleared(tracer_bin, tmp_path, scene):
    expected = alone(tracer_bin, scene, tmp_path / "alone")
    command = [tracer_bin, scene, "--width", "64", "--frames", "7", "--frame-list", "--threads", "1", "-q"]
    job = worker.worker_job("ahead-test", list(map(str, command)), ".png")
    worker.start_job(job)
    before = set(os.listdir(tempfile.gettempdir()))
    worker.ask_ahead(job, 1, 2)  # rendering from here on, before its task runs
    worker.ask_ahead(job, 5, 5)  # a second process; never claimed
    asked = {name for name in os.listdir(tempfile.gettempdir()) if name.startswith("tracer-frames-")} - before
    assert len(asked) == 2
    frames, _ = worker.render_frames(job, 1, 2)
    assert frames == [(1, expected[1]), (2, expected[2])]
    assert worker.render_frames(job, 3, 3)[0] == [(3, expected[3])]  # the first process, given back
    assert worker.close_job("ahead-test") == 2
    assert not asked & set(os.listdir(tempfile.gettempdir()))  # both folders removed, the unclaimed one too


def test_bad_animations_are_refused_before_any_frame(tracer_bin, tmp_path, scene):
    cases = [
        (["--frames", 3, "-o", tmp_path / "plain.png"], "number field", 2),
        (["--clock", "0:1", "-o", tmp_path / "f_#.png"], "--frames N", 2),
        (["--frames", 3, "--clock", "nan:1", "-o", tmp_path / "f_#.png"], "finite", 2),
        (["--frames", 3, "--subset", "5", "-o", tmp_path / "f_#.png"], "outside the animation's frames", 2),
        (["--frames", 3, "-o", tmp_path / "missing" / "f_#.png"], "no such folder", 3),
    ]
    for options, words, code in cases:
        result = farm(scene, *options, "--workers", 2, tracer=tracer_bin)
        assert result.returncode == code, (options, result.stderr)
        assert words in result.stderr, (options, result.stderr)
        assert "Traceback" not in result.stderr
    assert sorted(p.name for p in tmp_path.iterdir()) == ["zoom.scn"]
