#!/usr/bin/env python3
"""Hostile input: every class of the hostile-input issue, with the exit code, the message and
the fate of every file asserted. No crash, no hang, no memory blow-up, no lost file.

    test_hostile.py --tracer build/release/tracer

Time limits here only catch hangs (each is generous); speed is measured by benchmarks.
"""

import argparse
import json
import math
import os
import pathlib
import resource
import signal
import subprocess
import sys
import tempfile
import time
import unittest

ROOT = pathlib.Path(__file__).resolve().parents[2]
BUNNY = ROOT / "scenes" / "meshes" / "bunny.obj"
TRACER = ""
HANG = 60  # seconds: far beyond what any case here needs; reaching it means a hang

CAMERA = "camera { eye (0, 0, 7) lookat (0, 0, 0) }\n"
SMALL_SCENE = (
    CAMERA + "render { width 64 height 48 }\n"
    "sphere { center (0, 0, 0) radius 1 material { ka 0.1 kd (1, 0.5, 0.25) ks 0.5 n 20 } }\n"
    "light { position (2, 3, 4) color 2 }\n"
)
TRIANGLE = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"


def run(*args, limits=None, **kwargs):
    """Runs tracer; `limits` are (resource, value) pairs set in the child only."""

    def set_limits():
        signal.signal(signal.SIGXFSZ, signal.SIG_IGN)  # a file-size limit gives EFBIG, not a kill
        for which, value in limits or []:
            resource.setrlimit(which, (value, value))

    return subprocess.run([TRACER, *map(str, args)], capture_output=True, timeout=HANG, preexec_fn=set_limits, **kwargs)


def wait_until_handled(process, signum):
    """Waits until `process` catches `signum` (tracer installs its handlers just before it loads:
    a signal sent earlier kills it as usual), or has ended."""
    status = pathlib.Path(f"/proc/{process.pid}/status")
    while process.poll() is None:
        caught = next(line for line in status.read_text().splitlines() if line.startswith("SigCgt:"))
        if int(caught.split()[1], 16) & (1 << (signum - 1)):
            return
        time.sleep(0.005)


def peak_memory_mb(*args):
    """Runs tracer in a fresh Python process and returns (exit code, its peak resident MB)."""
    code = (
        "import resource, subprocess, sys\n"
        "r = subprocess.run(sys.argv[1:], capture_output=True)\n"
        "print(r.returncode, resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss // 1024)\n"
    )
    out = subprocess.run(
        [sys.executable, "-c", code, TRACER, *map(str, args)], capture_output=True, text=True, timeout=HANG
    )
    code, megabytes = out.stdout.split()
    return int(code), int(megabytes)


# The lines AddressSanitizer adds when an exception unwinds a stack over 64 MiB deep (besides its
# first, which names addresses): tracer clears the stack itself (base/big_stack.h).
ASAN_DEEP_STACK_WARNING = (
    "False positive error reports may follow",
    "For details see https://github.com/google/sanitizers/issues/189",
)


def sanitized():
    """True for an AddressSanitizer build (address-space limits do not apply to it)."""
    ldd = subprocess.run(["ldd", TRACER], capture_output=True, text=True)
    return "libasan" in ldd.stdout


class Hostile(unittest.TestCase):
    def setUp(self):
        self.dir = tempfile.TemporaryDirectory()
        self.tmp = pathlib.Path(self.dir.name)

    def tearDown(self):
        self.dir.cleanup()

    def write(self, name, content):
        path = self.tmp / name
        (path.write_bytes if isinstance(content, bytes) else path.write_text)(content)
        return path

    def mesh_scene(self, obj_name, extra=""):
        return self.write(
            "s.scn",
            CAMERA + f'mesh {{ file "{obj_name}" {extra} material {{ kd 1 }} }}\n' "light { position (0, 3, 3) }\n",
        )

    def files(self):
        return sorted(p.name for p in self.tmp.iterdir())

    def assertError(self, result, code, *fragments):
        stderr = result.stderr.decode(errors="replace")
        self.assertEqual(result.returncode, code, stderr)
        for fragment in fragments:
            self.assertIn(fragment, stderr)
        return stderr


class CrashesOnSmallFiles(Hostile):
    def test_line_ends_cr_only_crlf_and_mixed_read_the_same_faces(self):
        # Classic Mac line ends once hid face lines from the checker (out-of-range indices).
        self.write("m.obj", b"_\rf 1 3 1")
        self.assertError(
            run("--check", self.mesh_scene("m.obj")),
            1,
            "m.obj:2:3: error: vertex index 1 is out of range (the file has 0 vertices)",
        )
        for name, ending in [("cr", "\r"), ("crlf", "\r\n"), ("lf", "\n")]:
            self.write(f"{name}.obj", TRIANGLE.replace("\n", ending).encode())
            result = run("--check", self.mesh_scene(f"{name}.obj"))
            self.assertEqual(result.returncode, 0, result.stderr)

    def test_coordinates_beyond_float_range_are_refused(self):
        self.write("far.obj", "v 1e39 0 0\nv 0 1 0\nv 0 0 1\nf 1 2 3\n")
        self.assertError(run("--check", self.mesh_scene("far.obj")), 1, "far.obj:1:3: error: coordinate '1e39'")
        self.write("t.obj", TRIANGLE)
        self.assertError(run("--check", self.mesh_scene("t.obj", "scale 1e300")), 1, "must lie between")
        self.assertError(run("--check", self.mesh_scene("t.obj", "translate (1e308, 0, 0)")), 1, "must lie between")
        self.assertError(
            run("--check", self.mesh_scene("t.obj", "scale 1e29 translate (1e30, 0, 0)")),
            1,
            "reaches coordinates up to",
        )

    def test_numbers_that_overflow_a_parser(self):
        self.write("e.obj", "v 0 0 1e2147483648\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")
        self.assertError(run("--check", self.mesh_scene("e.obj")), 1, "is not a finite number")
        self.write("vt.obj", TRIANGLE + "vt 1e2147483648 0\n")  # texture coordinates: read and checked
        self.assertError(run("--check", self.mesh_scene("vt.obj")), 1, "is not a finite number")
        self.write("i.obj", TRIANGLE + "f 1 2 99999999999999999999\n")
        self.assertError(run("--check", self.mesh_scene("i.obj")), 1, "is not a valid face corner")

    def test_binary_file_as_mesh(self):
        self.write("b.obj", bytes(range(256)) * 64)
        stderr = self.assertError(run("--check", self.mesh_scene("b.obj")), 1, "NUL byte")
        self.assertLess(len(stderr), 2000)
        self.assertNotIn("\x00", stderr)

    def test_dump_json_of_a_path_that_is_not_utf8(self):
        folder = self.tmp / os.fsdecode(b"caf\xe9")
        folder.mkdir()
        (folder / "t.obj").write_text(TRIANGLE)
        scene = folder / "s.scn"
        scene.write_text(CAMERA + 'mesh { file "t.obj" material { kd 1 } }\n')
        result = run("--dump-json", scene)
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertIn("caf\ufffd", result.stdout.decode())


class Hangs(Hostile):
    def test_a_megabyte_of_nul_bytes(self):
        # One error for the run of bad bytes (the parser skips to the next statement quietly).
        nul_bytes = self.write("z.scn", bytes(1 << 20))
        stderr = self.assertError(run("--check", nul_bytes), 1, "unexpected character '\\x00'")
        self.assertEqual(stderr.count("unexpected character"), 1)
        self.assertLess(len(stderr), 20000)

    def test_ten_million_generated_blocks_stop_at_the_limit_in_bounded_memory(self):
        # Nested loops asking for 10^7 spheres: refused at 2,000,000 blocks, with the memory of a
        # scene that is never held whole (measured: 296 MB, 3.7 s on the reference machine).
        scene = self.write(
            "big.scn",
            "camera { eye (0, 0, 9) lookat (0, 0, 0) }\nlight { position (0, 5, 5) }\nmaterial m { kd 1 }\n"
            "for i in 0..10000 { for j in 0..1000 { sphere { center (i, j, 0) radius 0.4 material m } } }\n",
        )
        limits = [] if sanitized() else [(resource.RLIMIT_AS, 1 << 30)]
        self.assertError(
            run("--check", scene, limits=limits), 1, "the scene generates more than 2000000 blocks (the limit)"
        )

    def test_long_expressions_evaluate_or_stop_at_the_term_limit_in_bounded_memory(self):
        # a + b + ... is a tree as deep as it is long: parsed, compiled flat and taken apart
        # iteratively (before: a segmentation fault from 30,000 terms). 30,000 terms are a value,
        # in an entry, a let and a loop bound; a million are refused where the limit is passed
        # (100,000 terms or values in one statement), as are a million components (.x.x...).
        limits = [] if sanitized() else [(resource.RLIMIT_AS, 1 << 30)]
        for n in (30_000, 1_000_000):
            chain = "+".join(["1"] * n)
            product = "*".join(["1"] * n)
            cases = {
                "radius": f"sphere {{ center (0, 0, 0) radius {chain} - {n - 1} material {{ kd 1 }} }}\n",
                "let": f"let r = {product}\nsphere {{ center (0, 0, 0) radius r material {{ kd 1 }} }}\n",
                "loop": f"for i in 0..({chain}) - {n - 1} {{ sphere {{ center (0, 0, 0) radius 1 material m }} }}\n",
                "or": "let b = " + " or ".join(["false"] * n) + "\n",
                "list": "let l = [" + ", ".join(["1"] * n) + "]\n",
            }
            for name, text in cases.items():
                with self.subTest(terms=n, where=name):
                    scene = self.write(
                        "chain.scn", CAMERA + "light { position (0, 5, 5) }\nmaterial m { kd 1 }\n" + text
                    )
                    result = run("--check", scene, limits=limits)
                    if n < 100_000:
                        self.assertEqual(result.returncode, 0, result.stderr.decode(errors="replace")[-500:])
                    else:
                        self.assertError(result, 1, "in one statement (the limit)")
                        self.assertEqual(result.stderr.decode().count("error:"), 1)
            scene = self.write("dots.scn", CAMERA + "let v = (1, 2, 3)" + ".x" * n + "\n")
            self.assertError(run("--check", scene, limits=limits), 1, "the expression is nested too deeply")

    def test_the_language_s_other_limits_hold_in_bounded_time_and_memory(self):
        # Each an error at its place within the limits, never a crash, a hang or a blow-up: a
        # recursion 10^5 deep (the limit is 10,000 calls), loops of heavy bodies (5 x 10^8
        # operations), a list grown by recursion (10^6 items), a transform of 10^7 steps
        # (10,000 entries in a block), 10^5 nested conditions and a 10^8-byte string.
        limits = [] if sanitized() else [(resource.RLIMIT_AS, 1 << 30)]
        heavy = "".join(f"  let a{k} = i * {k}\n" for k in range(1000))
        cases = {
            "recursion": (
                "fn f(n) { return if n == 0 { 0 } else { 1 + f(n - 1) } }\nlet x = f(100000)\n",
                "calls nest more than 10000 deep (the limit)",
            ),
            # A shape value placing itself: a recursion that makes no value.
            "shape_value": ("let loop = group { loop }\nloop\n", "calls nest more than 10000 deep (the limit)"),
            "heavy": ("for i in 0..10000000 {\n" + heavy + "}\n", "the scene runs more than 500000000 operations"),
            # 10^7 iterations of one 10^4-term expression: few statements, much work (it ran for minutes).
            "terms": (
                "for i in 0..10000000 {\n  let t = " + " + ".join(["i"] * 10_000) + "\n}\n",
                "the scene runs more than 500000000 operations",
            ),
            "list": (
                "fn grow(n) { return if n == 0 { [] } else { [grow(n - 1), grow(n - 1)] } }\nlet l = grow(40)\n",
                "the scene makes more than 1000000 list items (the limit)",
            ),
            "transform": (
                'mesh { file "m.obj" material { kd 1 } transform {\n' + "scale 1\n" * 10_000_000 + "} }\n",
                "more than 10000 entries in one statement (the limit)",
            ),
            "conditions": (
                "let x = " + "if false { 1 } else " * 100_000 + "{ 2 }\n",
                "the expression is nested too deeply",
            ),
        }
        for name, (text, message) in cases.items():
            with self.subTest(case=name):
                if name in ("heavy", "terms") and sanitized():
                    # 5 x 10^8 operations take minutes under the sanitizers; the work limit's logic is
                    # checked there by tests/unit/lang (Interpreter.TheWorkLimitCountsOperations...).
                    self.skipTest("the whole work budget is too slow under the sanitizers")
                scene = self.write("limit.scn", CAMERA + "light { position (0, 5, 5) }\n" + text)
                result = run("--check", scene, limits=limits)
                self.assertError(result, 1, message)
                self.assertEqual(result.stderr.decode().count("error:"), 1, result.stderr.decode()[-800:])
        scene = self.write(
            "string.scn", CAMERA + 'let s = "' + "x" * 100_000_000 + '"\nfor i in 0..1000000 { let t = s }\n'
        )
        self.assertEqual(run("--check", scene, limits=limits).returncode, 0)

    def test_solids_nested_deep_and_wide_and_a_shape_minus_itself(self):
        # Solids (issue 55): 10^4 nested levels written out are one error at the nesting limit
        # (the 200 levels cut short say nothing more); 9,000 levels made by recursion, 10^5
        # parts of one difference and a sphere minus itself render, in bounded time and memory.
        limits = [] if sanitized() else [(resource.RLIMIT_AS, 1 << 30)]
        head = CAMERA + "render { width 32 height 24 }\nlight { position (0, 5, 5) }\nmaterial m { kd 1 }\n"
        sphere = "sphere { center (0, 0, 0) radius 1 material m }\n"
        cut = "sphere { center (0, 0, 1) radius 0.1 material m }\n"
        written = self.write("written.scn", head + "difference {\n" * 10_000 + sphere + (cut + "}\n") * 10_000)
        result = run("--check", written, limits=limits)
        stderr = self.assertError(result, 1, "statements are nested too deeply (more than 200 levels)")
        self.assertEqual(stderr.count("error:"), 1, stderr[-800:])
        recursive = head + (
            "fn nest(k) { if k == 0 { " + sphere + " } else { difference { nest(k - 1)\n"
            "  sphere { center (0, 0, 1) radius 0.1 * k / 9000 material m } } } }\nnest(9000)\n"
        )
        wide = head + (
            "difference { box { min (-1, -1, -1) max (1, 1, 1) material m }\n"
            "  for i in 0..100000 { sphere { center (random(1, i) * 2 - 1, random(2, i) * 2 - 1, 1) radius 0.01 "
            "material m } }\n}\n"
        )
        itself = head + "difference {\n" + sphere + sphere + "}\n"
        for name, text in {"recursive": recursive, "wide": wide, "itself": itself}.items():
            with self.subTest(case=name):
                scene = self.write(f"{name}.scn", text)
                out = self.tmp / f"{name}.png"
                result = run(scene, "-o", out, limits=limits)
                self.assertEqual(result.returncode, 0, result.stderr.decode()[-800:])
                self.assertTrue(out.is_file())

    def test_a_loop_including_a_big_file_compiles_it_once(self):
        # The file's text is held once and compiled once, at the include: each run of it costs
        # only what its statements do (here nothing), in bounded time and memory.
        self.write("big.scn", "# " + "x" * 1_000_000 + "\n")
        scene = self.write("loop.scn", SMALL_SCENE + 'for i in 0..100000 { include "big.scn" }\n')
        limits = [] if sanitized() else [(resource.RLIMIT_AS, 1 << 30)]
        result = run("--check", scene, limits=limits)
        self.assertEqual(result.returncode, 0, result.stderr)

    def test_many_includes_of_a_big_file_stop_at_the_included_text_limit(self):
        # Each include statement compiles the file in its own place: 300 of 1 MB pass 256 MiB.
        self.write("big.scn", "# " + "x" * 1_000_000 + "\n")
        scene = self.write("many.scn", SMALL_SCENE + 'include "big.scn"\n' * 300)
        limits = [] if sanitized() else [(resource.RLIMIT_AS, 1 << 30)]
        self.assertError(run("--check", scene, limits=limits), 1, "the scene includes more than 256 MiB of text in all")

    def test_fifo_and_devices_as_inputs(self):
        fifo = self.tmp / "pipe.obj"
        os.mkfifo(fifo)
        self.assertError(run("--check", self.mesh_scene("pipe.obj")), 1, "it is a FIFO, not a regular file")
        self.assertError(run("--check", fifo), 3, "it is a FIFO, not a regular file")
        self.assertError(run("--check", self.mesh_scene("/dev/zero")), 1, "it is a character device")
        self.assertError(run("--check", "/dev/zero"), 3, "it is a character device")
        self.assertError(run("--check", self.tmp), 3, "it is a directory")

    def test_faces_with_many_corners(self):
        n = 100_000
        star = [
            f"v {math.cos(2 * math.pi * i / n) * (1 if i % 2 else 0.9):.6f} "
            f"{math.sin(2 * math.pi * i / n) * (1 if i % 2 else 0.9):.6f} 0"
            for i in range(n)
        ]
        face = "f " + " ".join(str(i + 1) for i in range(n))
        self.write("star.obj", "\n".join(star) + "\n" + face + "\n")
        result = run("--check", self.mesh_scene("star.obj"))
        self.assertEqual(result.returncode, 0, result.stderr)
        self.write("huge.obj", "\n".join(star + star[:5]) + "\nf " + " ".join(str(i + 1) for i in range(n + 5)))
        self.assertError(run("--check", self.mesh_scene("huge.obj")), 1, "this face has more than 100000 corners")
        self.write("many.obj", "\n".join(star) + "\n" + (face + "\n") * 3)
        self.assertError(run("--check", self.mesh_scene("many.obj")), 1, "too large in all to triangulate")


class Memory(Hostile):
    def test_oversized_and_endless_inputs(self):
        big = self.tmp / "big.obj"
        with open(big, "wb") as f:
            f.truncate((1 << 30) + 1)  # sparse: takes no disk space
        self.assertError(run("--check", self.mesh_scene("big.obj")), 1, "the limit is 1.1 GB")
        os.truncate(big, (128 << 20) + 1)
        self.assertError(run("--check", big), 3, "the limit is 134.2 MB")

    def test_flat_shapes_from_a_loop_cost_a_few_hundred_bytes_per_triangle(self):
        # 2^18 shapes of each kind, the peak memory above the same scene with one shape, per
        # triangle. Each quad once took its own mesh, instance and copy of its source line: 915
        # bytes per triangle; now its description, its placed corners and its share of the
        # world (docs/bench/many-objects.md, "Many flat shapes"); the descriptions are freed once
        # placed, before the BVH is built. Under the sanitizers only the run is checked.
        shapes = {
            "quad": ("corner (i, j, 0) edge1 (0.5, 0, 0) edge2 (0, 0.5, 0)", 2, 240),
            "box": ("min (i, j, 0) max (i + 0.5, j + 0.5, 0.5)", 12, 150),
            "triangle": ("a (i, j, 0) b (i + 0.5, j, 0) c (i, j + 0.5, 0)", 1, 400),
        }
        for kind, (keys, triangles, most_bytes) in shapes.items():
            with self.subTest(kind=kind):
                peaks = []
                for side in (1, 512):
                    scene = self.write(
                        f"{kind}{side}.scn",
                        "camera { eye (256, 256, 700) lookat (256, 256, 0) }\nlight { position (0, 0, 900) }\n"
                        "material grey { kd 1 }\n"
                        f"for i in 0..{side} {{ for j in 0..{side} {{ {kind} {{ {keys} material grey }} }} }}\n",
                    )
                    code, megabytes = peak_memory_mb(scene, "-o", self.tmp / "q.png", "--width", "32", "-q")
                    self.assertEqual(code, 0)
                    peaks.append(megabytes)
                if not sanitized():
                    per_triangle = (peaks[1] - peaks[0]) * 2**20 / (512 * 512 * triangles)
                    self.assertLess(per_triangle, most_bytes)

    def test_dump_json_of_many_shapes_is_written_shape_by_shape(self):
        # 2^16 quads: the whole document held in memory took ~1.6 GB at 2^18 (6.3 GB at 10^6);
        # written entry by entry it needs the scene's description and one entry.
        scene = self.write(
            "q.scn",
            CAMERA + "material grey { kd 1 }\n"
            "for i in 0..256 { for j in 0..256 { quad { corner (i, j, 0) edge1 (0.5, 0, 0) edge2 (0, 0.5, 0) "
            "material grey } } }\n",
        )
        code, megabytes = peak_memory_mb("--dump-json", scene)
        self.assertEqual(code, 0)
        if not sanitized():
            self.assertLess(megabytes, 250)
        self.assertEqual(len(json.loads(run("--dump-json", scene).stdout)["quads"]), 65536)

    def test_many_warnings_are_capped(self):
        materials = " ".join(f"material m{i} {{ kd 1 }}" for i in range(20000))
        scene = self.write(
            "m.scn",
            CAMERA
            + materials
            + "\nlight { position (0, 5, 5) }\nplane { point (0, 0, 0) normal (0, 1, 0) material { kd 1 } }\n",
        )
        result = run("--check", scene)
        self.assertEqual(result.returncode, 0)
        self.assertIn(b"warning: 19980 more warnings not shown", result.stderr)
        self.assertLess(len(result.stderr), 200_000)
        code, megabytes = peak_memory_mb("--check", scene)
        self.assertEqual(code, 0)
        self.assertLess(megabytes, 500)

    def test_one_mesh_file_named_twenty_thousand_times(self):
        blocks = "".join(
            f'mesh {{ file "{BUNNY}" translate ({i % 100}, {i // 100}, 0) material {{ kd 1 }} }}\n'
            for i in range(20000)
        )
        scene = self.write("b.scn", CAMERA + blocks + "light { position (0, 3, 3) }\n")
        code, megabytes = peak_memory_mb(scene, "-o", self.tmp / "b.png", "--width", "32", "--height", "24", "-q")
        self.assertEqual(code, 0)
        self.assertLess(megabytes, 1000)

    def test_command_line_sizes_meet_the_pixel_cap(self):
        scene = self.write("s.scn", SMALL_SCENE)
        self.assertError(
            run(scene, "-o", self.tmp / "o.png", "--width", "16384", "--height", "16384"), 1, "the limit is 67108864"
        )
        self.assertEqual(self.files(), ["s.scn"])

    def test_out_of_memory_is_a_message_and_exit_3(self):
        if sanitized():
            self.skipTest("AddressSanitizer reserves its own address space; limits do not apply")
        scene = self.write("s.scn", SMALL_SCENE.replace("width 64 height 48", "width 8192 height 8192"))
        out = self.write("o.png", b"previous")
        result = run(scene, "-o", out, "-q", limits=[(resource.RLIMIT_AS, 600 << 20)])
        self.assertError(result, 3, "tracer: error: out of memory")
        self.assertEqual(out.read_bytes(), b"previous")
        self.assertEqual(self.files(), ["o.png", "s.scn"])


class Files(Hostile):
    def test_a_full_disk_keeps_the_old_output(self):
        scene = self.write("s.scn", SMALL_SCENE)
        for extension in ["png", "bmp", "jpg", "exr", "tif"]:
            out = self.write(f"o.{extension}", b"previous")
            result = run(scene, "-o", out, "-q", limits=[(resource.RLIMIT_FSIZE, 200)])
            self.assertError(result, 3, f"cannot write '{out}': file too large")
            self.assertEqual(out.read_bytes(), b"previous", extension)
            self.assertNotIn(".o.", result.stderr.decode())  # the temporary file is not named
        self.assertEqual(self.files(), ["o.bmp", "o.exr", "o.jpg", "o.png", "o.tif", "s.scn"])

    def test_outputs_never_replace_an_input(self):
        scene = self.write("s.png", SMALL_SCENE)  # a scene file with an image's name
        self.assertError(run(scene, "-o", scene), 2, "is the scene file")
        self.assertError(run(scene, "-o", self.tmp / "." / "s.png"), 2, "is the scene file")
        self.assertEqual(scene.read_text(), SMALL_SCENE)
        out = self.tmp / "o.png"
        self.assertError(run(scene, "-o", out, "--stats-json", scene), 2, "is the scene file")
        self.assertError(run(scene, "-o", out, "--stats-json", out), 2, "name the same file")
        self.write("m.png", TRIANGLE)  # a mesh file with an image's name
        mesh_scene = self.mesh_scene("m.png")
        self.assertError(run(mesh_scene, "-o", self.tmp / "m.png"), 2, "is a mesh file")
        self.assertEqual((self.tmp / "m.png").read_text(), TRIANGLE)
        self.assertEqual(self.files(), ["m.png", "s.png", "s.scn"])

    def test_outputs_never_replace_an_included_file(self):
        # The scene includes a file with an image's name: -o, --stats-json and a --region-list
        # line naming it are refused, and it is left as it was.
        included = "light { position (2, 3, 4) }\n"
        self.write("inc.png", included)
        scene = self.write("s.scn", SMALL_SCENE + 'include "inc.png"\n')
        self.assertError(run(scene, "-o", self.tmp / "inc.png"), 2, "is a file the scene includes")
        self.assertError(run(scene, "-o", self.tmp / "o.png", "--stats-json", self.tmp / "inc.png"), 2, "includes")
        region = f"0 0 8 8 {self.tmp / 'inc.png'}\n"
        result = run(scene, "--region-list", input=region.encode())  # answered line by line on stdout
        self.assertIn(b"is a file the scene includes", result.stdout)
        self.assertEqual((self.tmp / "inc.png").read_text(), included)
        self.assertEqual(self.files(), ["inc.png", "s.scn"])

    def test_output_paths_checked_before_rendering(self):
        scene = self.write("s.scn", SMALL_SCENE.replace("width 64 height 48", "width 4096 height 4096 samples 64"))
        started = time.monotonic()
        self.assertError(run(scene, "-o", self.tmp / "no" / "o.png"), 3, "no such folder")
        self.assertError(
            run(scene, "-o", self.tmp / "o.png", "--stats-json", self.tmp / "no" / "s.json"), 3, "no such folder"
        )
        (self.tmp / "d.png").mkdir()
        self.assertError(run(scene, "-o", self.tmp / "d.png"), 3, "it is a directory")
        self.assertLess(time.monotonic() - started, HANG)  # the 4096 x 4096 x 64 render never ran
        if os.geteuid() != 0:  # root may write anywhere
            locked = self.tmp / "locked"
            locked.mkdir(mode=0o555)
            stderr = self.assertError(run(scene, "-o", locked / "o.png"), 3, "cannot write in")
            self.assertNotIn(".tmp", stderr)
        self.assertEqual(self.files(), ["d.png", "s.scn"])

    def test_stats_json_is_written_whole(self):
        scene = self.write("s.scn", SMALL_SCENE)
        stats = self.write("s.json", b"previous")
        result = run(scene, "-o", self.tmp / "o.png", "-q", "--stats-json", stats)
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertIn('"rays"', stats.read_text())


class NumbersNeverWrongSilently(Hostile):
    def test_ten_thousand_area_lights_of_64_by_64_are_refused_at_once(self):
        # 4 x 10^7 samples: every point shaded would trace a shadow ray to each. One error, at the
        # light that crosses the bound, in well under a second (no render is tried).
        scene = self.write(
            "lights.scn",
            "camera { eye (0, 3, 9) lookat (0, 0, 0) }\nsphere { center (0, 0, 0) radius 1 material { kd 1 } }\n"
            "for i in 0..10000 {\n  area_light { position (i, 5, 0) edge1 (1, 0, 0) edge2 (0, 0, 1) "
            "samples1 64 samples2 64 }\n}\n",
        )
        result = run(scene, "-o", self.tmp / "lights.png")
        self.assertError(result, 1, "lights.scn:4:3: error: the scene's lights have 69632 samples", "more than 65536")
        self.assertEqual(result.stderr.count(b"error:"), 1, result.stderr)
        self.assertFalse((self.tmp / "lights.png").exists())

    def test_ray_weights_above_one_are_refused(self):
        # Two discs of kt 1e30, or 130 of kt 2, multiplied a shadow ray's weight to infinity.
        for key, value in (("kt", "2"), ("km", "1e30"), ("kt", "(0.5, 1.5, 0.5)")):
            scene = self.write("w.scn", SMALL_SCENE.replace("n 20", f"n 20 {key} {value}"))
            self.assertError(
                run("--check", scene), 1, f"'{key}' must be between 0 and 1", "weights above 1 multiply along a ray"
            )

    def test_placement_is_checked_as_composed_from_groups(self):
        # Two groups of scale 1e-20 made a sphere of radius 1e-40; one transform of the same two
        # steps was refused. Each shape is told, with its group.
        for shape in ("sphere { center (0, 0, 0) radius 1 material { kd 1 } }",
                      "box { min (0, 0, 0) max (1, 1, 1) scale 1e5 material { kd 1 } }"):  # fmt: skip
            scene = self.write(
                "g.scn",
                CAMERA + f"group {{ scale 1e-20 group {{ scale 1e-20 {shape} }} }}\nlight {{ position (0, 3, 3) }}\n",
            )
            self.assertError(
                run("--check", scene), 1, "on some axis by its own steps and its groups' together",
                "the innermost group placing it is here",
            )  # fmt: skip
        fine = self.write("f.scn", CAMERA + "group { scale 1e-10 group { scale 1e10 sphere { center (0, 0, 0) radius 1 "
                          "material { kd 1 } } } }\nlight { position (0, 3, 3) }\n")  # fmt: skip
        self.assertEqual(run("--check", fine).returncode, 0)

    def test_a_placement_after_a_statement_is_told_where_it_goes(self):
        scene = self.write(
            "t.scn",
            CAMERA + "group {\n  sphere { center (0, 0, 0) radius 1 material { kd 1 } }\n  translate (1, 0, 0)\n}\n",
        )
        self.assertError(run("--check", scene), 1, "t.scn:4:3: error: 'translate' here is read as a call",
                         "goes at the top of a group, before the group's first statement")  # fmt: skip

    def test_a_recursion_stopped_by_the_stack_says_so(self):
        # It said "calls nest more than 625 deep (the limit)" where the limit is 10,000 calls.
        deep = "1 + (" * 150 + "f(n + 1)" + ")" * 150
        scene = self.write("r.scn", "fn f(n) { return " + deep + " }\nlet x = f(0)\n" + CAMERA)
        stderr = self.assertError(run("--check", scene), 1, "of stack (about", "before the limit of 10000 calls)")
        self.assertNotIn("(the limit)", stderr)

    def test_a_runaway_recursion_is_told_in_at_most_12_lines(self):
        # 33 lines of identical call notes came before (innermost five, outermost four).
        for body in ("return f(n + 1)", "for i in 0..2 { f(n + 1) }"):
            scene = self.write("deep.scn", CAMERA + "fn f(n) {\n  " + body + "\n}\nlet x = 0\nf(0)\n")
            stderr = self.assertError(run("--check", scene), 1, "calls nest more than 10000 deep (the limit)")
            # Under AddressSanitizer, its three-line warning that it leaves the clearing of a stack
            # this deep to tracer (google/sanitizers issue 189) comes first.
            lines = [line for line in stderr.splitlines() if line not in ASAN_DEEP_STACK_WARNING]
            lines = [line for line in lines if "ASan is ignoring requested __asan_handle_no_return" not in line]
            self.assertLessEqual(len(lines), 12, stderr)
            self.assertIn("more levels of calls and loops: calls of 'f' ...", stderr)
            self.assertIn(":6:1: note: in this call of 'f'", stderr)  # the outermost

    def test_options_are_used_as_their_check_read_them(self):
        # --samples 4*4 was checked as 16 and rendered as 4 (the text read as an integer).
        dump = run("--dump-json", self.write("s.scn", SMALL_SCENE), "--samples", "4*4")
        self.assertEqual(dump.returncode, 0, dump.stderr)
        self.assertEqual(json.loads(dump.stdout)["render"]["samples"], 16)
        dump = run("--dump-json", self.tmp / "s.scn", "--width", "10*3", "--adaptive", "0.01*5:1+1:2*2")
        render = json.loads(dump.stdout)["render"]
        self.assertEqual((render["width"], render["adaptive_depth"], render["adaptive_cell"]), (30, 2, 4))
        self.assertAlmostEqual(render["adaptive_threshold"], 0.05)
        # A number that underflows is 0, as in a scene; it was "tracer: error: stod".
        tiny = run("--dump-json", self.tmp / "s.scn", "--adaptive", "1e-400")
        self.assertEqual(tiny.returncode, 0, tiny.stderr)
        self.assertEqual(json.loads(tiny.stdout)["render"]["adaptive_threshold"], 0)


class Messages(Hostile):
    def test_byte_order_mark_and_cr_only_scenes_are_read(self):
        bom = self.write("bom.scn", b"\xef\xbb\xbf" + SMALL_SCENE.encode())
        self.assertEqual(run("--check", bom).returncode, 0)
        cr = self.write("cr.scn", SMALL_SCENE.replace("\n", "\r").replace("radius 1", "radius -1").encode())
        self.assertError(run("--check", cr), 1, "cr.scn:3:")

    def test_a_megabyte_token_is_shown_cut(self):
        stderr = self.assertError(run("--check", self.write("t.scn", "x" * 1_000_000 + "\n")), 1, "...")
        self.assertLess(len(stderr), 2000)

    def test_extreme_focal_gives_the_same_image(self):
        images = []
        for focal in ["1", "1e-300", "1e30", "0.001"]:
            scene = self.write("f.scn", SMALL_SCENE.replace("lookat (0, 0, 0)", f"lookat (0, 0, 0) focal {focal}"))
            out = self.tmp / f"f{len(images)}.png"
            result = run(scene, "-o", out, "-q")
            self.assertEqual(result.returncode, 0, result.stderr)
            images.append(out.read_bytes())
        self.assertEqual(len(set(images)), 1)
        scene = self.write("f.scn", SMALL_SCENE.replace("lookat (0, 0, 0)", "lookat (0, 0, 0) focal 1e200"))
        self.assertError(run("--check", scene), 1, "'focal' must lie between -1e30 and 1e30")

    def test_eye_and_lookat_far_apart_or_very_close(self):
        far = self.write(
            "far.scn", SMALL_SCENE.replace("eye (0, 0, 7) lookat (0, 0, 0)", "eye (0, 0, 1e30) lookat (0, 0, -1e30)")
        )
        self.assertEqual(run("--check", far).returncode, 0)
        near = self.write(
            "near.scn",
            SMALL_SCENE.replace("eye (0, 0, 7) lookat (0, 0, 0)", "eye (0, 0, 7) lookat (0, 0, 6.999999999999999)"),
        )
        self.assertEqual(run(near, "-o", self.tmp / "n.png", "-q").returncode, 0)
        reference = self.tmp / "r.png"
        run(self.write("r.scn", SMALL_SCENE), "-o", reference, "-q")
        self.assertEqual((self.tmp / "n.png").read_bytes(), reference.read_bytes())

    def test_extreme_refraction_terminates_and_bad_ior_is_refused(self):
        # Full weights in every branch, indices of 1e-30 and 1e30, 50 levels: the branch budget
        # keeps the ray tree finite; an index of 0 has no meaning.
        evil = self.write(
            "glass.scn",
            CAMERA + "render { width 64 height 48 max_depth 50 }\n"
            "sphere { center (0, 0, 0) radius 1 material { kt 1 km 1 ior 1e-30 } }\n"
            "sphere { center (0, 0, -3) radius 1 material { kt 1 ior 1e30 } }\n"
            "light { position (2, 3, 4) }\n",
        )
        result = run(evil, "-o", self.tmp / "g.png", "-q")
        self.assertEqual(result.returncode, 0, result.stderr)
        bad = self.write("ior.scn", CAMERA + "sphere { center (0, 0, 0) radius 1 material { ior 0 } }\n")
        self.assertError(run("--check", bad), 1, "'ior' must be greater than 0, found 0")

    GLASS_HALL = (
        "camera { eye (0, 0, 0.5) lookat (1, 0.2, 0.5) fovy 60 }\n"
        "light { position (0, 0, 0.5) }\n"
        "material glass { kd 0.1 km 1 kt 1 ior 1.5 }\n"
        "for x in [-1, -0.5, 0.5, 1] { plane { point (x, 0, 0) normal (1, 0, 0) material glass } }\n"
    )

    def test_a_hall_of_glass_renders_within_the_ray_tree_bound(self):
        # Four parallel planes with km = kt = 1 at max_depth 100000: without a bound on the rays a
        # camera ray may spawn, one pixel took 41 s and the image hours.
        scene = self.write("hall.scn", self.GLASS_HALL + "render { width 16 height 12 max_depth 100000 }\n")
        stats = self.tmp / "stats.json"
        result = run(scene, "-o", self.tmp / "hall.png", "-q", "--stats-json", stats)
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertIn(b"reached the bound of 10000 reflected and refracted rays", result.stderr)
        rays = json.loads(stats.read_text())["rays"]
        self.assertGreater(rays["trees_cut"], 0)
        self.assertLessEqual(rays["reflection"] + rays["refraction"], 16 * 12 * 10_000)

    def test_sigint_stops_a_render_inside_the_ray_tree(self):
        # The same hall, big enough to render for minutes: Ctrl-C must stop it within a few hundred
        # rays of every thread's current pixel (checked inside the ray tree), exit 130, write nothing.
        scene = self.write("hall.scn", self.GLASS_HALL + "render { width 320 height 240 max_depth 100000 }\n")
        out = self.tmp / "hall.png"
        process = subprocess.Popen([TRACER, scene, "-o", out, "--threads", "2"], stderr=subprocess.PIPE)
        wait_until_handled(process, signal.SIGINT)
        time.sleep(0.5)  # rendering by now
        sent = time.monotonic()
        process.send_signal(signal.SIGINT)
        _, stderr = process.communicate(timeout=HANG)
        # A hang check, not a benchmark: the 100 ms of the README are measured in docs, on a
        # quiet machine; a shared CI machine running other tests gets a few seconds (the suite
        # failed once under ctest -j2 beside a fuzzer, not reproduced since: this is its one
        # timed check).
        self.assertLess(time.monotonic() - sent, 5.0)
        self.assertEqual(process.returncode, 130, stderr)
        self.assertIn(b"interrupted", stderr)
        self.assertEqual(self.files(), ["hall.scn"])

    def test_sigterm_while_loading_exits_130_and_writes_nothing(self):
        # A mesh of 320,000 triangles takes a good second to load and build.
        n = 400
        rows = [f"v {x} {y} 0" for y in range(n + 1) for x in range(n + 1)]
        faces = [
            f"f {y * (n + 1) + x + 1} {y * (n + 1) + x + 2} {(y + 1) * (n + 1) + x + 2} {(y + 1) * (n + 1) + x + 1}"
            for y in range(n)
            for x in range(n)
        ]
        self.write("grid.obj", "\n".join(rows + faces) + "\n")
        scene = self.mesh_scene("grid.obj", "scale 0.001")
        out = self.tmp / "o.png"
        process = subprocess.Popen([TRACER, scene, "-o", out, "--threads", "1"], stderr=subprocess.PIPE)
        wait_until_handled(process, signal.SIGTERM)
        process.send_signal(signal.SIGTERM)
        _, stderr = process.communicate(timeout=HANG)
        self.assertEqual(process.returncode, 130, stderr)
        # The same words as a render stopped half way (a signal while loading once said nothing).
        self.assertIn(b"tracer: interrupted; nothing written", stderr)
        self.assertEqual(self.files(), ["grid.obj", "s.scn"])

    def test_editor_input_binary_text_and_huge_names_give_json_not_a_crash(self):
        # --diagnostics json and --stdin-name take an editor's unsaved text: binary bytes, a NUL,
        # a 100,000-character name, a special file's name, 10^5 mistakes in a row.
        texts = {
            "binary": b"\xff\xfe bad \x00 bytes\n",
            "mistakes": (CAMERA + "sphere { radius r }\n" * 100_000).encode(),
        }
        for name in ("x" * 100_000, "/dev/zero", str(self.tmp / "sub" / "s.scn")):
            for kind, text in texts.items():
                with self.subTest(name=name[:20], kind=kind):
                    result = run("--check", "--diagnostics", "json", "--stdin-name", name, "-", input=text)
                    self.assertEqual(result.returncode, 1)
                    report = json.loads(result.stdout)  # one valid JSON line, whatever the bytes
                    self.assertFalse(report["ok"])
                    self.assertLessEqual(len(report["diagnostics"]), 200)
                    self.assertTrue(all(d["path"] == name for d in report["diagnostics"] if d["line"] > 0))


def main():
    global TRACER
    parser = argparse.ArgumentParser()
    parser.add_argument("--tracer", required=True)
    args, rest = parser.parse_known_args()
    TRACER = str(pathlib.Path(args.tracer).resolve())
    unittest.main(argv=[sys.argv[0], *rest])


if __name__ == "__main__":
    main()
