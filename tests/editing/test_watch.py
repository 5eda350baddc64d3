"""tracer --watch: a change to the scene, an include or a mesh gives a new image; a broken save
keeps the last image and reports the error; a burst of saves is rendered once, from the latest."""

import json
import os
import queue
import signal
import subprocess
import threading
import time

import numpy as np
import OpenImageIO as oiio
import pytest

SCENE = """camera {{ eye (0, 0, 7) lookat (0, 0, 0) }}
render {{ width {width} height 60 }}
include "colours.scn"
sphere {{ center (0, 0, 0) radius 1 material {{ kd (1, 1, 1) ka 0.1 }} }}
mesh {{ file "tri.obj" material {{ kd sphere_colour ka 0.1 }} translate (2, 0, 0) }}
light {{ position (2, 3, 4) color 1 }}
"""
TRIANGLE = "v -0.5 -0.5 0\nv 0.5 -0.5 0\nv 0 0.5 0\nf 1 2 3\n"


def save(path, text):
    """Writes `text` as an editor does: a new file renamed over the old one."""
    temporary = path.with_name(path.name + ".new")
    temporary.write_text(text)
    os.replace(temporary, path)


def pixels(path):
    image = oiio.ImageInput.open(str(path))
    spec = image.spec()
    data = np.asarray(image.read_image(oiio.UINT8)).reshape(spec.height, spec.width, spec.nchannels)
    image.close()
    return data


class Watcher:
    """tracer --watch --diagnostics json in the background; its events (one JSON object per line)
    arrive on a queue."""

    def __init__(self, tracer, scene, output):
        self.process = subprocess.Popen(
            [str(tracer), str(scene), "-o", str(output), "--watch", "--diagnostics", "json", "--threads", "2"],
            stdout=subprocess.PIPE,
            stderr=subprocess.PIPE,
            text=True,
        )
        self.events = queue.Queue()
        threading.Thread(target=self._read, daemon=True).start()

    def _read(self):
        for line in self.process.stdout:
            self.events.put(json.loads(line))

    def next(self, kind, stage=None, timeout=60):
        """The next event of `kind` (and `stage`), skipping others; fails after `timeout` s."""
        deadline = time.monotonic() + timeout
        while True:
            event = self.events.get(timeout=max(0.01, deadline - time.monotonic()))
            if event["event"] == kind and (stage is None or event.get("stage") == stage):
                return event

    def drain(self, seconds):
        """Every event of the next `seconds`."""
        time.sleep(seconds)
        out = []
        while not self.events.empty():
            out.append(self.events.get())
        return out

    def until(self, done, timeout=60):
        """Every event up to the first for which done(event) holds; fails after `timeout` s (a
        margin for a loaded machine, not a measure of speed)."""
        deadline, out = time.monotonic() + timeout, []
        while not out or not done(out[-1]):
            out.append(self.events.get(timeout=max(0.01, deadline - time.monotonic())))
        return out

    def stop(self):
        self.process.send_signal(signal.SIGINT)
        return self.process.wait(timeout=30)


@pytest.fixture
def project(tmp_path):
    (tmp_path / "colours.scn").write_text("let sphere_colour = (1, 0, 0)\n")
    (tmp_path / "tri.obj").write_text(TRIANGLE)
    scene = tmp_path / "scene.scn"
    scene.write_text(SCENE.format(width=80))
    return scene


def test_changes_to_the_scene_an_include_and_a_mesh_each_give_a_new_image(tracer_bin, project, tmp_path):
    output = tmp_path / "out.png"
    watcher = Watcher(tracer_bin, project, output)
    try:
        first = watcher.next("load")
        assert first["ok"], first["text"]
        assert {os.path.basename(p) for p in first["files_read"]} == {"scene.scn", "colours.scn", "tri.obj"}
        watcher.next("image", "full")
        assert pixels(output).shape[:2] == (60, 80)
        red = pixels(output)

        save(project, SCENE.format(width=100))  # the scene
        watcher.next("load")
        assert watcher.next("image", "full")["width"] == 100
        assert pixels(output).shape[:2] == (60, 100)

        save(tmp_path / "colours.scn", "let sphere_colour = (0, 0, 1)\n")  # an included file
        watcher.next("load")
        watcher.next("image", "full")
        blue = pixels(output)
        assert (blue[..., 2].astype(int) - blue[..., 0]).max() > 100, "the mesh turned blue"

        save(tmp_path / "tri.obj", TRIANGLE.replace("0 0.5 0", "0 1.5 0"))  # a mesh
        watcher.next("load")
        watcher.next("image", "full")
        taller = pixels(output)
        assert np.count_nonzero(taller[..., 2] > 100) > np.count_nonzero(blue[..., 2] > 100), "a taller triangle"
        assert red.shape != taller.shape or not np.array_equal(red, taller)
    finally:
        assert watcher.stop() == 130


def test_a_broken_save_keeps_the_last_image_and_reports_the_error(tracer_bin, project, tmp_path):
    output = tmp_path / "out.png"
    watcher = Watcher(tracer_bin, project, output)
    try:
        watcher.next("image", "full")
        good = output.read_bytes()
        save(project, SCENE.format(width=80).replace("radius 1", "radius r"))
        event = watcher.next("load")
        assert not event["ok"]
        assert event["diagnostics"][0]["line"] == 4
        assert "undefined name 'r'" in event["diagnostics"][0]["message"]
        assert "^" in event["text"]
        assert not [e for e in watcher.drain(0.5) if e["event"] == "image"]
        assert output.read_bytes() == good, "the last good image stays"
        save(project, SCENE.format(width=80).replace("radius 1", "radius 0.5"))  # fixed
        assert watcher.next("load")["ok"]
        watcher.next("image", "full")
        assert output.read_bytes() != good
    finally:
        assert watcher.stop() == 130


def test_a_burst_of_saves_renders_the_latest_only(tracer_bin, project, tmp_path):
    output = tmp_path / "out.png"
    watcher = Watcher(tracer_bin, project, output)
    try:
        watcher.next("image", "full")
        watcher.drain(0.2)
        started = time.monotonic()
        for width in range(81, 91):
            save(project, SCENE.format(width=width))
        took = time.monotonic() - started
        events = watcher.until(lambda e: e["event"] == "image" and e["stage"] == "full" and e["width"] == 90)
        events += watcher.drain(0.5)  # nothing more should follow the last save's image
        loads = [e for e in events if e["event"] == "load"]
        images = [e for e in events if e["event"] == "image" and e["stage"] == "full"]
        if took < 0.03:  # within the 40 ms that make one change (a loaded machine may take longer)
            assert len(loads) == 1, events
            assert [e["width"] for e in images] == [90]
        else:  # saves further apart may each be a change of their own, but the last image is the last save's
            assert len(loads) <= 10 and images[-1]["width"] == 90, events
        assert pixels(output).shape[:2] == (60, 90)
    finally:
        assert watcher.stop() == 130


def test_a_save_during_a_long_render_cancels_it(tracer_bin, tmp_path):
    scene = tmp_path / "slow.scn"
    slow = """camera { eye (0, 0, 7) lookat (0, 0, 0) }
render { width 2000 height 2000 samples 64 }
sphere { center (0, 0, 0) radius 1 material { kd 0.8 } }
light { position (2, 3, 4) color 1 }
"""
    scene.write_text(slow)
    output = tmp_path / "out.png"
    watcher = Watcher(tracer_bin, scene, output)
    try:
        watcher.next("image", "preview")
        save(scene, slow.replace("width 2000 height 2000 samples 64", "width 40 height 30"))
        changed = watcher.next("changed")
        assert changed["cancelled_render"]
        event = watcher.next("image", "full", timeout=20)
        assert (event["width"], event["height"]) == (40, 30)
    finally:
        assert watcher.stop() == 130


def test_watch_refuses_what_it_cannot_do(tracer_bin, project, tmp_path):
    for arguments in (["--check"], ["--region", "0", "0", "4", "4"], ["--stats-json", str(tmp_path / "s.json")]):
        result = subprocess.run(
            [str(tracer_bin), str(project), "-o", str(tmp_path / "o.png"), "--watch", *arguments],
            capture_output=True,
            text=True,
            timeout=30,
        )
        assert result.returncode == 2, arguments
        assert "--watch" in result.stderr


def test_the_bound_on_ray_trees_is_reported_as_a_render_reports_it(tracer_bin, tmp_path):
    # Four parallel glass planes at max_depth 100000 (tests/cli/test_hostile.py's hall): camera
    # rays reach the bound of 10,000 rays a tree, which the image events count and note.
    scene = tmp_path / "hall.scn"
    scene.write_text(
        "camera { eye (0, 0, 0.5) lookat (1, 0.2, 0.5) fovy 60 }\nlight { position (0, 0, 0.5) }\n"
        "material glass { kd 0.1 km 1 kt 1 ior 1.5 }\n"
        "for x in [-1, -0.5, 0.5, 1] { plane { point (x, 0, 0) normal (1, 0, 0) material glass } }\n"
        "render { width 16 height 12 max_depth 100000 }\n"
    )
    watcher = Watcher(tracer_bin, scene, tmp_path / "hall.png")
    try:
        event = watcher.next("image", "full")
        assert event["trees_cut"] > 0
        assert "reached the bound of 10000 reflected and refracted rays" in event["note"]
    finally:
        assert watcher.stop() == 130
