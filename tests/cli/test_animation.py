#!/usr/bin/env python3
"""Animation through the command line: the clock's values at each frame (first, last, one frame,
cyclic, a clock range), the scene compiled once and its mesh read and built once (--stats-json),
numbered outputs, a frame of a subset equal to the same frame of the whole run, resuming, and
every kind of interruption leaving only whole files; hostile: 10^7 frames, a pattern without a
number field, a NaN clock, a subset outside the frames, an output folder that vanishes."""

import argparse
import json
import pathlib
import shutil
import signal
import subprocess
import sys
import tempfile
import time
import unittest

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
from test_images import read_png  # noqa: E402

TRACER = ""
MESH = pathlib.Path(__file__).resolve().parents[2] / "scenes" / "meshes" / "bunny.obj"

# A square filling the view, lit by its ambient term alone: every pixel is (frame_number,
# clock, |clock_delta|) / 255 as 8-bit values, exactly when those are whole numbers.
CLOCK_SCENE = """render { width 2 height 2 }
camera { eye (0, 0, 1) lookat (0, 0, 0) fovy 90 }
quad { corner (-2, -2, 0) edge1 (4, 0, 0) edge2 (0, 4, 0)
  material { ka (frame_number, clock, abs(clock_delta)) / 255 } }
"""

# A bunny that moves with the clock, in front of a sphere.
MESH_SCENE = f"""render {{ width 48 height 36 }}
camera {{ eye (0, 1, 6) lookat (0, 0.5, 0) fovy 40 }}
light {{ position (3, 5, 4) }}
sphere {{ center (0, 0, -2) radius 1 material {{ kd (0.8, 0.3, 0.2) }} }}
mesh {{ file "{MESH}" scale 0.2 translate (2 * clock - 1, -0.5, 0) material {{ kd (0.7, 0.7, 0.9) }} }}
"""


def pixel(path):
    return read_png(path)[0][0]


def whole_png(path):
    """True if the file decodes completely as tracer's PNGs do (and ends with IEND)."""
    try:
        data = path.read_bytes()
        return data.endswith(b"IEND\xaeB`\x82") and len(read_png(path)) > 0
    except Exception:  # a truncated or foreign file
        return False


class Animation(unittest.TestCase):
    def setUp(self):
        self.folder = pathlib.Path(tempfile.mkdtemp())
        self.addCleanup(shutil.rmtree, self.folder, True)

    def scene(self, text, name="scene.scn"):
        path = self.folder / name
        path.write_text(text)
        return path

    def run_tracer(self, *arguments, timeout=120):
        return subprocess.run([TRACER, *map(str, arguments)], capture_output=True, text=True, timeout=timeout)

    def frames(self, scene, *options, pattern="f_##.png"):
        result = self.run_tracer(scene, "-q", "-o", self.folder / pattern, *options)
        self.assertEqual(result.returncode, 0, result.stderr)
        return result

    def test_the_clock_at_each_frame(self):
        scene = self.scene(CLOCK_SCENE)
        cases = [  # options, then (frame_number, clock, clock_delta) at each frame made
            (["--frames", "8", "--clock", "0:70"], [(i, 10 * i, 10) for i in range(8)]),
            (["--frames", "8", "--clock", "0:80", "--cyclic"], [(i, 10 * i, 10) for i in range(8)]),
            (["--frames", "6", "--clock", "200:100"], [(i, 200 - 20 * i, 20) for i in range(6)]),  # counting down
            (["--frames", "1", "--clock", "40:90"], [(0, 40, 0)]),
            (["--frames", "11", "--clock", "0:100", "--subset", "3:5"], [(i, 10 * i, 10) for i in (3, 4, 5)]),
        ]
        for options, expected in cases:
            with self.subTest(options=options):
                for old in self.folder.glob("f_*.png"):
                    old.unlink()
                self.frames(scene, *options)
                made = sorted(self.folder.glob("f_*.png"))
                self.assertEqual([p.name for p in made], [f"f_{e[0]:02d}.png" for e in expected])
                self.assertEqual([pixel(p) for p in made], [tuple(e) for e in expected])

    def test_a_still_image_has_the_clock_at_zero_and_dump_json_shows_one_frame(self):
        scene = self.scene(CLOCK_SCENE)
        result = self.run_tracer(scene, "-q", "-o", self.folder / "still.png")
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertEqual(pixel(self.folder / "still.png"), (0, 0, 0))
        dumped = self.run_tracer(scene, "--dump-json", "--frames", "5", "--clock", "0:2", "--subset", "3")
        self.assertEqual(dumped.returncode, 0, dumped.stderr)
        ka = json.loads(dumped.stdout)["quads"][0]["material"]["ka"]
        self.assertEqual(ka, [3 / 255, 1.5 / 255, 0.5 / 255])

    def test_the_scene_is_compiled_once_and_its_mesh_read_and_built_once(self):
        scene = self.scene(MESH_SCENE)
        stats = self.folder / "stats.json"
        self.frames(scene, "--frames", "4", "--stats-json", stats)
        figures = json.loads(stats.read_text())
        self.assertEqual(figures["scene_compilations"], 1)
        self.assertEqual(figures["mesh_files_read"], 1)
        self.assertEqual(figures["mesh_builds"], 1)
        self.assertEqual(figures["frames_rendered"], 4)
        self.assertEqual([f["frame"] for f in figures["frames"]], [0, 1, 2, 3])
        images = [read_png(self.folder / f"f_0{i}.png") for i in range(4)]
        self.assertEqual(len({str(image) for image in images}), 4)  # the bunny moved in each

    def test_a_frame_of_a_subset_is_the_frame_of_the_whole_run_bit_for_bit(self):
        scene = self.scene(MESH_SCENE)
        self.frames(scene, "--frames", "5", "--cyclic")
        for frame in (0, 3):
            one = self.folder / f"one_{frame}.png"
            result = self.run_tracer(scene, "-q", "--frames", "5", "--cyclic", "--subset", frame, "-o", one)
            self.assertEqual(result.returncode, 0, result.stderr)
            self.assertEqual(one.read_bytes(), (self.folder / f"f_0{frame}.png").read_bytes())

    def test_number_fields_are_padded_and_grow_past_their_width(self):
        scene = self.scene(CLOCK_SCENE)
        self.frames(scene, "--frames", "12", pattern="frame#.png")
        names = sorted(p.name for p in self.folder.glob("frame*.png"))
        self.assertEqual(names, sorted(f"frame{i}.png" for i in range(12)))
        self.frames(scene, "--frames", "2", pattern="x_####_y.ppm")
        self.assertTrue((self.folder / "x_0001_y.ppm").is_file())

    def test_resume_keeps_whole_frames_and_makes_the_rest(self):
        scene = self.scene(MESH_SCENE)
        self.frames(scene, "--frames", "6")
        original = {i: (self.folder / f"f_0{i}.png").read_bytes() for i in range(6)}
        (self.folder / "f_01.png").unlink()
        (self.folder / "f_02.png").write_bytes(original[2][: len(original[2]) // 2])  # cut short
        small = self.scene(MESH_SCENE.replace("width 48 height 36", "width 24 height 18"), "small.scn")
        result = self.run_tracer(small, "-q", "--frames", "6", "--subset", "4", "-o", self.folder / "f_##.png")
        self.assertEqual(result.returncode, 0, result.stderr)  # f_04 now of another size
        stats = self.folder / "stats.json"
        self.frames(scene, "--frames", "6", "--resume", "--stats-json", stats)
        figures = json.loads(stats.read_text())
        self.assertEqual((figures["frames_kept"], figures["frames_rendered"]), (3, 3))
        self.assertEqual([f["frame"] for f in figures["frames"] if f.get("kept")], [0, 3, 5])
        for i in range(6):
            self.assertEqual((self.folder / f"f_0{i}.png").read_bytes(), original[i], i)

    def test_bad_frame_options_are_usage_errors(self):
        scene = self.scene(CLOCK_SCENE)
        out = self.folder / "f_#.png"
        cases = [
            (["--frames", "10000000", "-o", out], "1 to 1000000 frames"),
            (["--frames", "0", "-o", out], "1 to 1000000 frames"),
            (["--frames", "3", "-o", self.folder / "plain.png"], "number field"),
            (["--frames", "3", "--clock", "nan:1", "-o", out], "finite"),
            (["--frames", "3", "--clock", "0:inf", "-o", out], "finite"),
            (["--frames", "3", "--clock", "1", "-o", out], "FIRST:LAST"),
            (["--frames", "8", "--subset", "5:2", "-o", out], "FIRST <= LAST"),
            (["--frames", "8", "--subset", "9", "-o", out], "outside the animation's frames 0 to 7"),
            (["--clock", "0:1", "-o", out], "--frames N"),
            (["--frames", "3", "--watch", "-o", out], "--subset F"),
            (["--frames", "3", "--dump-json"], "--subset F"),
        ]
        for options, words in cases:
            with self.subTest(options=options):
                result = self.run_tracer(scene, *options)
                self.assertEqual(result.returncode, 2, result.stderr)
                self.assertIn(words, result.stderr)
                self.assertNotIn("Traceback", result.stderr)
        self.assertEqual(list(self.folder.glob("f_*")) + list(self.folder.glob("plain*")), [])

    def test_a_frame_with_an_error_stops_the_run_after_the_frames_before_it(self):
        scene = self.scene(CLOCK_SCENE.replace("fovy 90", "fovy 90 - 30 * frame_number"))  # fovy 0 at 3
        result = self.run_tracer(scene, "-q", "--frames", "6", "-o", self.folder / "f_#.png")
        self.assertEqual(result.returncode, 1)
        self.assertIn("scene.scn:2:", result.stderr)
        self.assertIn("frame 3", result.stderr)
        self.assertEqual(sorted(p.name for p in self.folder.glob("f_*")), ["f_0.png", "f_1.png", "f_2.png"])
        check = self.run_tracer(scene, "--check", "--frames", "6")
        self.assertEqual(check.returncode, 1)
        self.assertIn("frame 3", check.stderr)
        good = self.run_tracer(self.scene(CLOCK_SCENE, "good.scn"), "--check", "--frames", "6")
        self.assertEqual(good.returncode, 0, good.stderr)
        self.assertIn("frames: ok at each of 6 (0 to 5)", good.stdout)
        self.assertIn("image: 2 x 2 pixels", good.stdout)

    def test_a_frame_list_renders_each_run_asked_for_as_the_whole_run_does(self):
        scene = self.scene(MESH_SCENE)
        self.frames(scene, "--frames", "6")
        requests = (
            f"0 1 {self.folder}/list_#.png\n"
            "\n"
            f"4 4 {self.folder}/four.png\n"
            "7 7 x.png\n"  # outside the frames: refused, the process goes on
            f"2 3 {self.folder}/plain.png\n"  # two frames, one name: refused
            f"5 5 {self.folder}/list_#.png\n"
        )
        result = subprocess.run(
            [TRACER, scene, "--frames", "6", "--frame-list", "-q"], input=requests, capture_output=True, text=True
        )
        self.assertEqual(result.returncode, 0, result.stderr)
        replies = result.stdout.splitlines()
        self.assertEqual(replies[:2], ["done 0 1", "done 4 4"])
        self.assertTrue(replies[2].startswith("error: expected 'FIRST LAST PATTERN'"), replies)
        self.assertIn("no number field", replies[3])
        self.assertEqual(replies[4], "done 5 5")
        for frame, name in ((0, "list_0.png"), (1, "list_1.png"), (4, "four.png"), (5, "list_5.png")):
            self.assertEqual((self.folder / name).read_bytes(), (self.folder / f"f_0{frame}.png").read_bytes())
        refused = self.run_tracer(scene, "--frames", "6", "--frame-list", "-o", self.folder / "f_#.png")
        self.assertEqual(refused.returncode, 2)
        self.assertIn("--frame-list takes each run", refused.stderr)

    def start_long_run(self, frames, folder):
        scene = self.scene(MESH_SCENE.replace("width 48 height 36", "width 320 height 240 samples 4"), "long.scn")
        return subprocess.Popen(
            [TRACER, scene, "-q", "--frames", str(frames), "-o", folder / "f_####.png"],
            stdout=subprocess.PIPE,
            stderr=subprocess.PIPE,
            text=True,
        )

    def interrupt_after_the_first_frame(self, act):
        """Starts a long run, waits for its first frame, calls act(process, folder) and returns
        (exit code, stderr, folder); a run that ended first is started again with more frames."""
        for frames in (40, 400, 4000):
            folder = pathlib.Path(tempfile.mkdtemp(dir=self.folder))
            process = self.start_long_run(frames, folder)
            while not (folder / "f_0000.png").exists() and process.poll() is None:
                time.sleep(0.005)
            if process.poll() is None:
                act(process, folder)
                _, stderr = process.communicate(timeout=300)
                return process.returncode, stderr, folder, frames
            process.communicate()
        self.fail("every run ended before it could be interrupted")

    def test_ctrl_c_between_or_during_frames_leaves_only_whole_frames(self):
        code, stderr, folder, frames = self.interrupt_after_the_first_frame(
            lambda process, _: process.send_signal(signal.SIGINT)
        )
        self.assertEqual(code, 130, stderr)
        self.assertIn("interrupted", stderr)
        made = sorted(folder.iterdir())
        self.assertGreaterEqual(len(made), 1)
        self.assertLess(len(made), frames)
        self.assertTrue(all(p.name.startswith("f_") and p.suffix == ".png" for p in made), made)  # no temporary
        self.assertTrue(all(whole_png(p) for p in made))
        # Resumed: the frames there are kept, the rest made.
        result = self.run_tracer(
            self.folder / "long.scn", "-q", "--frames", 3, "--resume", "-o", folder / "f_####.png", timeout=300
        )
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertTrue(all(whole_png(folder / f"f_{i:04d}.png") for i in range(3)))

    def test_an_output_folder_that_vanishes_mid_run_is_an_error_with_the_frames_before_it_kept(self):
        def remove_folder(process, folder):
            process.send_signal(signal.SIGSTOP)  # no frame is written while the folder goes
            shutil.rmtree(folder)
            process.send_signal(signal.SIGCONT)

        code, stderr, folder, _ = self.interrupt_after_the_first_frame(remove_folder)
        self.assertEqual(code, 3, stderr)
        self.assertIn("cannot write", stderr)
        self.assertIn("frames before it are written", stderr)
        self.assertNotIn("Traceback", stderr)


if __name__ == "__main__":
    parser = argparse.ArgumentParser()
    parser.add_argument("--tracer", required=True)
    args, rest = parser.parse_known_args()
    TRACER = str(pathlib.Path(args.tracer).resolve())
    unittest.main(argv=[sys.argv[0], *rest])
