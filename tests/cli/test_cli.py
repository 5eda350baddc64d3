#!/usr/bin/env python3
"""The command line's contract: exit codes, nothing written on failure, the JSON dump.

test_cli.py --tracer build/release/tracer
"""

import argparse
import hashlib
import json
import pathlib
import signal
import subprocess
import sys
import tempfile
import time
import unittest

ROOT = pathlib.Path(__file__).resolve().parents[2]
TASK2 = ROOT / "scenes" / "task2.scn"
TRACER = ""

SMALL_SCENE = """camera { eye (0, 0, 7) lookat (0, 0, 0) }
render { width 64 height 48 }
sphere { center (0, 0, 0) radius 1 material { ka 0.1 kd (1, 0.5, 0.25) ks 0.5 n 20 } }
light { position (2, 3, 4) color 2 }
"""


def to_10_digits(value):
    """A JSON value with every number as text of 10 significant digits, and without the meshes'
    "bounds" (facts of their files, computed with whatever rounding the build has)."""
    if isinstance(value, float):
        return format(value, ".10g")
    if isinstance(value, list):
        return [to_10_digits(v) for v in value]
    if isinstance(value, dict):
        return {k: to_10_digits(v) for k, v in value.items() if k != "bounds"}
    return value


def run(*args, **kwargs):
    return subprocess.run([TRACER, *map(str, args)], capture_output=True, text=True, timeout=120, **kwargs)


class CommandLine(unittest.TestCase):
    def setUp(self):
        self.dir = tempfile.TemporaryDirectory()
        self.tmp = pathlib.Path(self.dir.name)
        self.small = self.tmp / "small.scn"
        self.small.write_text(SMALL_SCENE)

    def tearDown(self):
        self.dir.cleanup()

    def leftovers(self):
        return sorted(p.name for p in self.tmp.iterdir() if p.name != "small.scn" and not p.name.endswith(".scn"))

    def test_help_and_version(self):
        self.assertEqual(run("--help").returncode, 0)
        self.assertIn("Exit codes", run("--help").stdout)
        version = run("--version")
        self.assertEqual(version.returncode, 0)
        self.assertRegex(version.stdout, r"tracer \d+\.\d+\.\d+")

    def test_usage_errors_exit_2(self):
        self.assertEqual(run().returncode, 2)
        self.assertEqual(run(self.small).returncode, 2)  # no -o
        self.assertEqual(run("--no-such-option", self.small).returncode, 2)
        self.assertEqual(run(self.small, "-o", self.tmp / "a.png", "--threads", "0").returncode, 2)
        self.assertEqual(run("--check", "--dump-json", self.small).returncode, 2)
        self.assertEqual(run(self.small, "-o", self.tmp / "a.png", "--samples", "5").returncode, 2)  # not N*N
        self.assertEqual(run(self.small, "-o", self.tmp / "a.png", "--width", "0").returncode, 2)
        self.assertEqual(self.leftovers(), [])

    def test_size_and_samples_override_the_render_block(self):
        # One of width and height alone keeps the scene's aspect ratio (64 x 48: 4 to 3).
        for size, expected in (
            (["--width", "32"], (32, 24)),
            (["--height", "12"], (16, 12)),
            (["--width", "7"], (7, 5)),
        ):
            render = json.loads(run("--dump-json", self.small, *size).stdout)["render"]
            self.assertEqual((render["width"], render["height"]), expected)
        result = run("--dump-json", self.small, "--width", "30", "--height", "20", "--samples", "9")
        self.assertEqual(result.returncode, 0, result.stderr)
        render = json.loads(result.stdout)["render"]
        self.assertEqual((render["width"], render["height"], render["samples"]), (30, 20, 9))
        out = self.tmp / "out.png"
        result = run(self.small, "-o", out, "--width", "30", "--height", "20", "--samples", "4")
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertIn("30x20, 4 spp", result.stderr)

    def test_adaptive_antialiasing_from_the_command_line(self):
        result = run("--dump-json", self.small, "--adaptive", "0.02:4")
        self.assertEqual(result.returncode, 0, result.stderr)
        render = json.loads(result.stdout)["render"]
        self.assertEqual(
            (render["antialias"], render["adaptive_threshold"], render["adaptive_depth"]), ("adaptive", 0.02, 4)
        )
        self.assertEqual(
            json.loads(run("--dump-json", self.small, "--adaptive", "0.1").stdout)["render"]["adaptive_depth"], 3
        )
        render = json.loads(run("--dump-json", self.small, "--adaptive", "0.1:2:8").stdout)["render"]
        self.assertEqual((render["adaptive_depth"], render["adaptive_cell"]), (2, 8))
        out = self.tmp / "out.png"
        result = run(self.small, "-o", out, "--adaptive", "0.05:2")
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertRegex(result.stderr, r"64x48, \d+\.\d\d \(adaptive\) spp")
        # The scene's values are checked by its rules, the option's by the same rules.
        for value, message in (
            ("2", "'adaptive_threshold' must be between 0 and 1, found 2"),
            ("0.1:9", "'adaptive_depth' must be between 0 and 8, found 9"),
            ("abc", "'adaptive_threshold' expects a number, found 'abc'"),
            ("0.1:", "expected THRESHOLD[:DEPTH[:CELL]], e.g. 0.05:3 or 0.05:3:4"),
            ("0.1:3:4:1", "expected THRESHOLD[:DEPTH[:CELL]], e.g. 0.05:3 or 0.05:3:4"),
            ("0.1:3:3", "'adaptive_cell' must be a power of two (..., 0.5, 1, 2, 4, ...); try 2 or 4"),
            ("0.1:3:32", "'adaptive_cell' must be between 0.00390625 and 16, found 32"),
        ):
            with self.subTest(value=value):
                result = run(self.small, "-o", out, "--adaptive", value)
                self.assertEqual(result.returncode, 2)
                self.assertIn(f"--adaptive: {message}", result.stderr)
        result = run(self.small, "-o", out, "--adaptive", "0.1", "--samples", "4")
        self.assertEqual(result.returncode, 1)
        self.assertIn("'samples' is for uniform antialiasing", result.stderr)
        result = run(self.small, "-o", out, "--adaptive", "0.1:2:0.125")
        self.assertEqual(result.returncode, 1)
        self.assertIn("'adaptive_cell' 0.125 is finer than the 1/4 pixel that 'adaptive_depth' 2", result.stderr)

    def test_overrides_are_checked_by_the_scene_rules(self):
        # Each override against the same key written in the scene's render block: refused alike,
        # with the same message (CLI11 puts the option's name before it), or accepted alike.
        cases = {
            "width": ["0", "16385", "10.5", "nan", "abc", "300", "4096"],
            "height": ["-1", "1e9", "2", "(1, 2, 3)"],
            "samples": ["8", "0", "4097", "16", "9"],
            "max_depth": ["-1", "100001", "0", "7"],
            "leaf_size": ["0", "256", "8"],
            "accel": ["fast", "bvh", "median", "1"],
        }
        for key, values in cases.items():
            for value in values:
                with self.subTest(key=key, value=value):
                    scene = self.tmp / "override.scn"
                    scene.write_text(
                        SMALL_SCENE.replace("render { width 64 height 48 }", f"render {{ {key} {value} }}")
                    )
                    in_scene = run("--check", scene)
                    option = "--" + key.replace("_", "-")
                    on_command_line = run("--check", self.small, option, value)
                    if in_scene.returncode == 0:
                        self.assertEqual(on_command_line.returncode, 0, on_command_line.stderr)
                        continue
                    self.assertEqual(in_scene.returncode, 1)
                    self.assertEqual(on_command_line.returncode, 2)
                    message = in_scene.stderr.splitlines()[0].split(": error: ", 1)[1]
                    if message.startswith("undefined name"):
                        # A scene may define names; the command line has none, so a word there
                        # is a value of the wrong kind.
                        self.assertIn(f"{option}: '{key}' expects", on_command_line.stderr)
                        self.assertIn(f"found '{value}'", on_command_line.stderr)
                        continue
                    self.assertIn(f"{option}: {message}", on_command_line.stderr)

    def test_shipped_scenes_describe_the_same_scene_as_before_the_interpreter(self):
        # The hashes were taken from the parser that read scenes before names, loops and
        # expressions existed: every scene must still mean exactly the same.
        lines = (pathlib.Path(__file__).parent / "scene_descriptions.sha256").read_text().splitlines()
        entries = [line.split() for line in lines if line and not line.startswith("#")]
        self.assertGreaterEqual(len(entries), 19)
        for expected, relative in entries:
            with self.subTest(scene=relative):
                result = run("--dump-json", ROOT / relative)
                self.assertEqual(result.returncode, 0, result.stderr)
                scene = json.loads(result.stdout)
                scene.pop("source")
                text = json.dumps(to_10_digits(scene), sort_keys=True).replace(str(ROOT), "<root>")
                self.assertEqual(hashlib.sha256(text.encode()).hexdigest(), expected)

    def test_parameters_from_the_command_line(self):
        scene = self.tmp / "param.scn"
        scene.write_text("param r = 0.5\nparam tint = (1, 1, 1)\n" + SMALL_SCENE.replace("radius 1", "radius r"))
        dumped = json.loads(run("--dump-json", scene).stdout)
        self.assertEqual(dumped["parameters"], {"r": 0.5, "tint": [1.0, 1.0, 1.0]})
        self.assertEqual(dumped["spheres"][0]["radius"], 0.5)
        result = run("--dump-json", scene, "-D", "r=0.25 * 3", "--define", "tint=(1, 0, 0)")
        self.assertEqual(result.returncode, 0, result.stderr)
        dumped = json.loads(result.stdout)
        self.assertEqual(dumped["parameters"], {"r": 0.75, "tint": [1.0, 0.0, 0.0]})
        self.assertEqual(dumped["spheres"][0]["radius"], 0.75)
        # An unknown name, a bad value, a value the scene refuses, and no '=' at all.
        result = run("--check", scene, "-D", "radius=2")
        self.assertEqual(result.returncode, 1)
        self.assertIn("<command line>: error: -D radius: the scene has no 'param radius'", result.stderr)
        result = run("--check", scene, "-D", "r=(1,")
        self.assertEqual(result.returncode, 1)
        self.assertIn("<command line>: error: -D r=(1,: expected a value, found end of file", result.stderr)
        result = run("--check", scene, "-D", "r=-1")
        self.assertEqual(result.returncode, 1)
        self.assertIn("error: 'radius' must be greater than 0, found -1", result.stderr)
        self.assertEqual(run("--check", scene, "-D", "r").returncode, 2)

    def test_check_and_dump_json_state_mesh_facts(self):
        scene = self.tmp / "facts.scn"
        obj = ROOT / "scenes" / "meshes" / "cube.obj"
        scene.write_text(
            "camera { eye (0, 0, 7) lookat (0, 0, 0) }\nlight { position (2, 3, 4) }\n"
            f'mesh {{ file "{obj}" transform {{ scale (2, 1, 1) translate (0, 1, 0) }} material {{ kd 1 }} }}\n'
            "quad { corner (0, 0, 0) edge1 (0, 0, 1) edge2 (1, 0, 0) material { kd 1 } }\n"
        )
        result = run("--check", scene)
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertIn("1 mesh, 1 quad, 1 light", result.stdout)
        self.assertIn(
            "mesh cube.obj (line 3): 12 triangles, 8 vertices, placed within (-2, 0, -1) to (2, 2, 1)", result.stdout
        )
        dumped = json.loads(run("--dump-json", scene).stdout)
        mesh = dumped["meshes"][0]
        self.assertEqual((mesh["triangles"], mesh["vertices"]), (12, 8))
        self.assertEqual(mesh["bounds"], [[-2.0, 0.0, -1.0], [2.0, 2.0, 1.0]])
        self.assertEqual(mesh["transform"], [{"scale": [2.0, 1.0, 1.0]}, {"translate": [0.0, 1.0, 0.0]}])
        self.assertNotIn("scale", mesh)
        self.assertEqual(dumped["quads"][0]["edge1"], [0.0, 0.0, 1.0])
        self.assertEqual(dumped["quads"][0]["scale"], [1.0, 1.0, 1.0])

    def test_scene_from_standard_input(self):
        # "-" reads the scene from standard input; mesh paths are relative to the working folder.
        (self.tmp / "meshes").mkdir()
        (self.tmp / "meshes" / "t.obj").write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")
        mesh_scene = SMALL_SCENE + 'mesh { file "meshes/t.obj" material { kd 1 } }\n'
        result = run("--check", "-", input=mesh_scene, cwd=self.tmp)
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertTrue(result.stdout.startswith("<stdin>: ok"), result.stdout)
        out = self.tmp / "from_stdin.png"
        result = run("-", "-o", out, "-q", input=SMALL_SCENE, cwd=self.tmp)
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertEqual(out.read_bytes()[:4], b"\x89PNG")
        result = run("--check", "-", input="camera { eye (0, 0, 7) lookat (0, 0, 0) }\nsphere { radius 1 }\n")
        self.assertEqual(result.returncode, 1)
        self.assertTrue(result.stderr.startswith("<stdin>:2:1: error: sphere is missing"), result.stderr)
        # --region-list reads its regions from standard input too: it cannot also hold the scene
        # (it exited 0 silently, the regions' text taken as part of the scene).
        result = run("-", "--region-list", input=SMALL_SCENE)
        self.assertEqual(result.returncode, 2)
        self.assertIn("the scene cannot come from there too", result.stderr)
        # More than a scene file may hold: refused, as a file would be (exit 3).
        result = run("--check", "-", input=" " * ((128 << 20) + 1))
        self.assertEqual(result.returncode, 3)
        self.assertIn("<stdin>: error: cannot read the scene file: more than the limit of 134.2 MB", result.stderr)

    def test_diagnostics_as_json_for_other_programs(self):
        # --diagnostics json: one line of JSON on stdout, the same diagnostics as the text, with
        # the text itself; --stdin-name checks unsaved text as if it were that file (an editor).
        (self.tmp / "sub").mkdir()
        (self.tmp / "sub" / "lib.scn").write_text("let r = 0.5\n")
        text = (
            SMALL_SCENE.replace("radius 1", "radius r")
            + 'include "lib.scn"\nsphere { center (1, 0, 0) radius 1 material { kd 1 } fuzz 2 }\n'
        )
        result = run(
            "--check", "--diagnostics", "json", "--stdin-name", self.tmp / "sub" / "unsaved.scn", "-", input=text
        )
        self.assertEqual(result.returncode, 1)
        self.assertEqual(result.stderr, "")
        lines = result.stdout.splitlines()
        self.assertEqual(len(lines), 1)
        report = json.loads(lines[0])
        self.assertFalse(report["ok"])
        self.assertEqual(report["errors"], 2)
        first, second = report["diagnostics"]
        self.assertEqual((first["line"], first["column"], first["length"]), (3, 34, 1))
        self.assertEqual(first["message"], "undefined name 'r'")
        self.assertEqual(second["line"], 6)
        self.assertIn("unknown key 'fuzz'", second["message"])
        self.assertTrue(first["path"].endswith("unsaved.scn"))
        text_run = run("--check", "--stdin-name", self.tmp / "sub" / "unsaved.scn", "-", input=text)
        self.assertEqual(report["text"], text_run.stderr)
        self.assertEqual(first["text"] + second["text"], text_run.stderr)
        self.assertEqual([pathlib.Path(p).name for p in report["files_read"]], ["lib.scn"])  # found beside the name
        # The names the scene defines, each with its kind and place (for editors' completion).
        named = "let a = 1\nmaterial m { kd 1 }\nfn f(x) { return x }\nfor i in 0..2 { let b = i }\n"
        names = json.loads(run("--check", "--diagnostics", "json", "-", input=SMALL_SCENE + named).stdout)["names"]
        self.assertEqual(
            [(n["name"], n["kind"], n["line"], n["column"]) for n in names],
            [
                ("a", "let", 5, 5),
                ("m", "material", 6, 10),
                ("f", "fn", 7, 4),
                ("x", "parameter", 7, 6),
                ("i", "for", 8, 5),
                ("b", "let", 8, 21),
            ],
        )
        good = run("--check", "--diagnostics", "json", self.small)
        self.assertEqual(good.returncode, 0)
        self.assertEqual(json.loads(good.stdout)["ok"], True)
        self.assertEqual(run("--dump-json", "--diagnostics", "json", self.small).returncode, 2)
        self.assertEqual(run("--check", "--stdin-name", "x.scn", self.small).returncode, 2)
        self.assertEqual(run("--check", "--diagnostics", "sarif", self.small).returncode, 2)

    def test_language_json_holds_the_tables(self):
        language = json.loads(run("--language-json").stdout)
        blocks = {block["kind"]: block for block in language["blocks"]}
        self.assertIn("sphere", blocks)
        radius = next(key for key in blocks["sphere"]["keys"] if key["name"] == "radius")
        self.assertEqual(radius["type"], "a number")
        self.assertIn("fovy", [key["name"] for key in blocks["camera"]["keys"]])
        self.assertIn("let", [s["keyword"] for s in language["statements"]])
        self.assertIn("sqrt", [f["name"] for f in language["functions"]])
        self.assertIn("pi", [c["name"] for c in language["constants"]])

    def test_render_writes_png_and_summary(self):
        out = self.tmp / "out.png"
        result = run(self.small, "-o", out, "--threads", "2")
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertTrue(out.exists())
        self.assertEqual(out.read_bytes()[:8], b"\x89PNG\r\n\x1a\n")
        self.assertRegex(result.stderr, r"64x48, 1 spp, 2 threads, .* Mrays/s")
        self.assertEqual(self.leftovers(), ["out.png"])  # no temporary file left behind
        quiet = run(self.small, "-o", out, "--quiet")
        self.assertEqual((quiet.returncode, quiet.stderr), (0, ""))

    def test_exr_output(self):
        out = self.tmp / "out.exr"
        result = run(self.small, "-o", out)
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertEqual(out.read_bytes()[:4], b"\x76\x2f\x31\x01")  # OpenEXR magic number

    def test_srgb_encoding_of_8_bit_files(self):
        # A plane of ambient colour fills the view: every pixel is its ka, linear or encoded by
        # the sRGB curve (computed here from IEC 61966-2-1); a PNG says which in its chunks.
        ka = (0.002, 0.2, 0.9)
        scene = self.tmp / "flat.scn"
        scene.write_text(
            "render { width 4 height 2 }\ncamera { eye (0, 0, 5) lookat (0, 0, 0) }\nlight { position (0, 5, 5) "
            f"color 0 }}\nplane {{ point (0, 0, 0) normal (0, 0, 1) material {{ ka ({ka[0]}, {ka[1]}, {ka[2]}) }} }}\n"
        )

        def encoded(v):
            return 12.92 * v if v <= 0.0031308 else 1.055 * v ** (1 / 2.4) - 0.055

        def pixels(*options):  # binary PPM: header, then the 8 pixels' bytes
            out = self.tmp / "out.ppm"
            self.assertEqual(run(scene, "-o", out, *options).returncode, 0)
            return list(out.read_bytes()[len(b"P6\n4 2\n255\n") :])

        self.assertEqual(pixels(), [round(255 * v) for v in ka] * 8)
        self.assertEqual(pixels("--encoding", "srgb"), [round(255 * encoded(v)) for v in ka] * 8)
        scene.write_text(scene.read_text().replace("width 4", "width 4 encoding srgb"))
        self.assertEqual(pixels(), [round(255 * encoded(v)) for v in ka] * 8)
        self.assertEqual(pixels("--encoding", "linear"), [round(255 * v) for v in ka] * 8)

        def chunks(path):
            data, at, kinds = path.read_bytes(), 8, []
            while at < len(data):
                kinds.append(data[at + 4 : at + 8].decode())
                at += 12 + int.from_bytes(data[at : at + 4], "big")
            return kinds

        for encoding, marked in (("linear", False), ("srgb", True)):
            run(scene, "-o", self.tmp / "out.png", "--encoding", encoding)
            self.assertEqual("sRGB" in chunks(self.tmp / "out.png"), marked, encoding)
        # Float files stay linear: the same bytes either way (HDR: an EXR holds the time it was written).
        run(scene, "-o", self.tmp / "a.hdr", "--encoding", "srgb")
        run(scene, "-o", self.tmp / "b.hdr", "--encoding", "linear")
        self.assertEqual((self.tmp / "a.hdr").read_bytes(), (self.tmp / "b.hdr").read_bytes())
        self.assertGreater((self.tmp / "a.hdr").stat().st_size, 8 * 4)
        self.assertIn('"encoding": "srgb"', run("--dump-json", scene).stdout)

    def test_scene_errors_exit_1_and_write_nothing(self):
        bad = self.tmp / "bad.scn"
        bad.write_text(SMALL_SCENE.replace("radius 1", "radius -1"))
        out = self.tmp / "out.png"
        result = run(bad, "-o", out)
        self.assertEqual(result.returncode, 1)
        self.assertIn("bad.scn:3:", result.stderr)
        self.assertFalse(out.exists())
        self.assertEqual(self.leftovers(), [])

    def test_failed_render_keeps_an_existing_output(self):
        out = self.tmp / "out.png"
        out.write_bytes(b"previous image")
        bad = self.tmp / "bad.scn"
        bad.write_text("camera {")
        self.assertEqual(run(bad, "-o", out).returncode, 1)
        self.assertEqual(out.read_bytes(), b"previous image")

    def test_unreadable_scene_or_output_exit_3(self):
        missing = run(self.tmp / "missing.scn", "-o", self.tmp / "out.png")
        self.assertEqual(missing.returncode, 3)
        self.assertIn("missing.scn: error: cannot read the scene file", missing.stderr)
        self.assertEqual(run("--check", self.tmp).returncode, 3)  # a directory
        self.assertEqual(run(self.small, "-o", self.tmp / "out.unknownformat").returncode, 3)
        self.assertEqual(run(self.small, "-o", self.tmp / "no" / "such" / "folder.png").returncode, 3)
        self.assertEqual(self.leftovers(), [])

    def test_interrupted_render_writes_nothing(self):
        big = self.tmp / "big.scn"
        big.write_text(SMALL_SCENE.replace("width 64 height 48", "width 4096 height 4096 samples 64"))
        out = self.tmp / "out.png"
        proc = subprocess.Popen([TRACER, big, "-o", out, "--threads", "1"], stderr=subprocess.PIPE, text=True)
        time.sleep(1.0)
        proc.send_signal(signal.SIGINT)
        _, stderr = proc.communicate(timeout=60)
        self.assertEqual(proc.returncode, 130, stderr)
        self.assertIn("interrupted; nothing written", stderr)
        self.assertFalse(out.exists())
        self.assertEqual(self.leftovers(), [])

    def test_interrupted_render_leaves_no_process_behind(self):
        # After Ctrl-C a helper sharing tracer's memory frees it once tracer is gone
        # (base/fast_exit.h). Run as a subreaper, this script adopts the helper and waits for it:
        # it must end by itself, with code 0, holding none of tracer's streams.
        big = self.tmp / "big.scn"
        big.write_text(SMALL_SCENE.replace("width 64 height 48", "width 4096 height 4096 samples 64"))
        script = (
            "import ctypes, os, signal, subprocess, sys, time\n"
            "ctypes.CDLL(None, use_errno=True).prctl(36, 1, 0, 0, 0)  # PR_SET_CHILD_SUBREAPER\n"
            "proc = subprocess.Popen(sys.argv[2:], stderr=subprocess.PIPE, stdout=subprocess.PIPE)\n"
            "time.sleep(float(sys.argv[1]))\n"
            "proc.send_signal(signal.SIGINT)\n"
            "out, err = proc.communicate()  # end of file on both: nothing else holds them\n"
            "print('tracer', proc.returncode)\n"
            "while True:\n"
            "    try:\n"
            "        pid, status = os.waitpid(-1, 0)\n"
            "    except ChildProcessError:\n"
            "        break\n"
            "    print('helper', os.waitstatus_to_exitcode(status))\n"
        )
        # A Ctrl-C before the render starts (loading, slow under a sanitizer on a busy machine) ends
        # tracer at once with no helper: then again, the signal later, until one lands in the render.
        for delay in (1, 2, 4, 8, 16):
            result = subprocess.run(
                [sys.executable, "-c", script, str(delay), TRACER, big, "-o", self.tmp / "out.png", "--threads", "1"],
                capture_output=True,
                text=True,
                timeout=120,
            )
            if result.stdout.split("\n")[:2] != ["tracer 130", ""]:
                break
        self.assertEqual(result.stdout.split("\n")[:2], ["tracer 130", "helper 0"], result.stderr)
        self.assertFalse((self.tmp / "out.png").exists())

    def test_names_change_by_assignment_and_while_loops(self):
        # `total = total + i` changes the outer name (a `let` there made a new one, silently);
        # `while` runs under the loop limit; a function keeps the values it was defined with.
        scene = self.tmp / "change.scn"
        scene.write_text(
            "camera { eye (0, 0, 10) lookat (0, 0, 0) }\nlight { position (0, 5, 5) }\n"
            "let total = 0\nfor i in 0..5 { total = total + i }\n"
            "let n = 0\nwhile n < 3 { n = n + 1 }\n"
            "fn seen() { return total }\ntotal = total + 100\n"
            "sphere { center (n, seen(), total) radius 1 material { kd 1 } }\n"
        )
        result = run("--dump-json", scene)
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertEqual(json.loads(result.stdout)["spheres"][0]["center"], [3.0, 10.0, 110.0])
        forever = self.tmp / "forever.scn"
        forever.write_text("camera { eye (0, 0, 10) lookat (0, 0, 0) }\nlet n = 0\nwhile true { n = n + 1 }\n")
        result = run("--check", forever)
        self.assertEqual(result.returncode, 1)
        self.assertIn(
            "forever.scn:3:1: error: the scene runs more than 10000000 loop iterations (the limit)", result.stderr
        )

    def test_strings_join_str_reads_back_and_print_writes_in_order(self):
        # str(x) writes the shortest text that reads back as x exactly; print writes each line
        # where and when it runs, on stderr and in --diagnostics json.
        rng = __import__("random").Random(53)
        numbers = [0.1, 1 / 3, 1e-30, 5e-324, 1.7976931348623157e308, -2.5, 100000.0, 123456789012345680.0]
        numbers += [rng.uniform(-1, 1) * 10 ** rng.randint(-300, 300) for _ in range(200)]
        scene = self.tmp / "strings.scn"
        lines = [f"print(str({x!r}))" for x in numbers]
        scene.write_text(
            "camera { eye (0, 0, 10) lookat (0, 0, 0) }\nlight { position (0, 5, 5) }\n"
            'let name = "a" + "/" + str(2) + ".obj"\n'
            + "\n".join(lines)
            + '\nfor i in 0..2 { print("i is", i, (i, 0, 1), [i, "x", true]) }\nprint(name)\n'
        )
        result = run("--check", scene)
        self.assertEqual(result.returncode, 0, result.stderr)
        printed = [line.split(": print: ", 1) for line in result.stderr.splitlines() if ": print: " in line]
        self.assertEqual([float(text) for _, text in printed[: len(numbers)]], numbers)
        self.assertEqual(printed[len(numbers)][0], f"{scene}:{len(numbers) + 4}:17")
        self.assertEqual(
            [text for _, text in printed[len(numbers) :]],
            ['i is 0 (0, 0, 1) [0, "x", true]', 'i is 1 (1, 0, 1) [1, "x", true]', "a/2.obj"],
        )
        report = json.loads(run("--check", scene, "--diagnostics", "json").stdout.splitlines()[0])
        self.assertEqual(report["prints"][-1]["text"], "a/2.obj")
        self.assertEqual(report["prints"][-1]["line"], len(numbers) + 5)
        # A loop that prints a million lines keeps the first thousand and counts the rest.
        loud = self.tmp / "loud.scn"
        loud.write_text("camera { eye (0, 0, 10) lookat (0, 0, 0) }\nfor i in 0..1000000 { print(i) }\n")
        result = run("--check", loud)
        self.assertEqual(result.stderr.count(": print: "), 1000)
        self.assertIn("print: 999000 more lines printed, not shown", result.stderr)

    def test_check_reports_ok_on_stdout(self):
        result = run("--check", TASK2)
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertIn("ok (4 spheres, 2 planes, 0 meshes, 2 lights, 5 materials)", result.stdout)
        # One of a kind in the singular; cylinders (equal radii) apart from cones.
        result = run("--check", ROOT / "scenes" / "round_shapes.scn")
        self.assertIn(
            "ok (0 spheres, 1 plane, 0 meshes, 1 cylinder, 2 cones, 1 disc, 2 lights, 5 materials)", result.stdout
        )

    def test_dump_json_is_resolved(self):
        result = run("--dump-json", TASK2)
        self.assertEqual(result.returncode, 0, result.stderr)
        scene = json.loads(result.stdout)
        self.assertEqual(scene["source"], str(TASK2))
        self.assertEqual(
            scene["render"],
            {
                "width": 1200,
                "height": 800,
                "max_depth": 4,
                "samples": 1,
                "background": [0.0, 0.0, 0.0],
                "shadows": True,
                "accel": "sah",
                "leaf_size": 4,
            },
        )
        self.assertEqual(scene["camera"]["fovy"], 45.0)
        self.assertEqual(len(scene["spheres"]), 4)
        self.assertEqual(scene["spheres"][3]["radius"], 1.0)
        self.assertEqual(scene["spheres"][3]["material"]["km"], [0.8, 0.8, 0.8])
        self.assertEqual(scene["planes"][1]["normal"], [0.0, 0.0, 1.0])
        self.assertEqual(scene["lights"][1], {"position": [-2.0, 1.0, 4.0], "color": [0.5, 0.5, 0.5]})

    def test_dump_json_of_a_bad_scene_prints_nothing_on_stdout(self):
        bad = self.tmp / "bad.scn"
        bad.write_text("camera { eye (0, 0, 7) }")
        result = run("--dump-json", bad)
        self.assertEqual((result.returncode, result.stdout), (1, ""))

    def test_stats_and_accelerator_options(self):
        mesh_scene = self.tmp / "mesh.scn"
        obj = ROOT / "scenes" / "meshes" / "tetrahedron.obj"
        mesh_scene.write_text(
            SMALL_SCENE.replace("sphere {", f'mesh {{ file "{obj}" material {{ kd 1 }} }}\nsphere {{')
        )
        stats_path = self.tmp / "stats.json"
        images = {}
        for accel in ("none", "box", "median", "sah"):
            out = self.tmp / f"{accel}.png"
            result = run(mesh_scene, "-o", out, "--accel", accel, "--stats", "--stats-json", stats_path)
            self.assertEqual(result.returncode, 0, result.stderr)
            self.assertRegex(result.stderr, r"mesh tetrahedron.obj \(line 3\): 4 triangles, " + accel)
            self.assertRegex(result.stderr, r"objects: 1 spheres, 0 planes, 1 mesh instances")
            self.assertRegex(
                result.stderr,
                r"per ray [0-9.]+ object box tests, [0-9.]+ object tests, "
                r"[0-9.]+ mesh box tests, [0-9.]+ triangle tests",
            )
            stats = json.loads(stats_path.read_text())
            self.assertEqual(stats["accel"], accel)
            self.assertEqual(stats["meshes"][0]["triangles"], 4)
            self.assertEqual((stats["meshes"][0]["blocks"], stats["meshes"][0]["placed"]), (1, True))
            self.assertEqual(stats["objects"]["bounded_objects"], 2)
            self.assertEqual(stats["rays"]["primary"], 64 * 48)
            images[accel] = out.read_bytes()
        self.assertEqual(len(set(images.values())), 1)  # every accelerator, the same image
        self.assertEqual(run(mesh_scene, "-o", self.tmp / "x.png", "--accel", "kd-tree").returncode, 2)

    def test_reference_matches_committed_file(self):
        self.assertEqual(run("--reference").stdout, (ROOT / "grammar" / "reference.md").read_text())


if __name__ == "__main__":
    parser = argparse.ArgumentParser()
    parser.add_argument("--tracer", required=True)
    args, rest = parser.parse_known_args()
    TRACER = str(pathlib.Path(args.tracer).resolve())
    unittest.main(argv=[sys.argv[0], *rest], verbosity=1)
