#!/usr/bin/env python3
"""The standard library and the include search path (issue 53): `include "std/..."` finds the
files built into tracer wherever the scene is (and whatever is on disk), every name they define
is used by a committed scene, their numbers are what their comments say (the sRGB decoding and
the Fresnel reflectance computed here independently), and an include not beside its file is
looked for in the -I folders, then TRACER_PATH's, in order."""

import argparse
import json
import os
import pathlib
import re
import subprocess
import sys
import tempfile
import unittest

TRACER = ""
ROOT = pathlib.Path(__file__).resolve().parents[2]
LIBRARY = ROOT / "src" / "lang" / "std"
CAMERA = "camera { eye (0, 0, 5) lookat (0, 0, 0) }\nlight { position (0, 5, 5) }\n"


def run(*args, env=None, stdin=None):
    return subprocess.run([TRACER, *map(str, args)], capture_output=True, text=True, env=env, input=stdin, timeout=120)


def defined_names(text):
    """The names a library file defines at the start of a line (`let NAME` and `fn NAME`)."""
    return re.findall(r"^(?:let|fn) ([a-z_][a-z_0-9]*)", text, re.MULTILINE)


def srgb_decoded(value):
    """IEC 61966-2-1's decoding of an 8-bit sRGB value to linear, written from the standard."""
    c = value / 255
    return c / 12.92 if c <= 0.04045 else ((c + 0.055) / 1.055) ** 2.4


class StandardLibrary(unittest.TestCase):
    def setUp(self):
        self.folder = tempfile.TemporaryDirectory()
        self.dir = pathlib.Path(self.folder.name)

    def tearDown(self):
        self.folder.cleanup()

    def write(self, name, text):
        path = self.dir / name
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(text)
        return path

    def printed(self, result):
        """The values print() wrote, one list of words per line."""
        return [line.split("print: ", 1)[1] for line in result.stderr.splitlines() if "print: " in line]

    def test_every_name_of_the_library_is_used_by_a_committed_scene(self):
        files = sorted(LIBRARY.glob("*.scn"))
        self.assertGreaterEqual(len(files), 2)
        scenes = "\n".join(p.read_text() for p in (ROOT / "scenes").rglob("*.scn"))
        for file in files:
            names = defined_names(file.read_text())
            self.assertTrue(names, file)
            for name in names:
                used = re.search(rf"\b{name}\b", scenes)
                self.assertTrue(used, f"{file.name}: '{name}' is used by no scene in scenes/")
            self.assertIn(f'include "std/{file.name}"', scenes)

    def test_the_library_is_found_from_any_folder_and_from_standard_input(self):
        scene = 'include "std/colors.scn"\ninclude "std/materials.scn"\n' + CAMERA + "print(tomato)\n"
        for path in (self.write("a/b/c/deep.scn", scene), self.write("top.scn", scene)):
            result = run("--check", path)
            self.assertEqual(result.returncode, 0, result.stderr)
        result = run("--check", "-", stdin=scene)
        self.assertEqual(result.returncode, 0, result.stderr)
        # A folder called std beside the scene is not looked at: std/ is the library's.
        self.write("std/colors.scn", "let tomato = 0\n")
        result = run("--check", self.write("shadow.scn", scene))
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertTrue(self.printed(result)[0].startswith("(1, 0.12"), result.stderr)

    def test_the_library_files_are_built_in_not_files_read(self):
        path = self.write("s.scn", 'include "std/colors.scn"\n' + CAMERA)
        report = json.loads(run("--check", "--diagnostics", "json", path).stdout.splitlines()[0])
        self.assertEqual(report["files_read"], [str(path)])
        self.assertTrue(any(n["path"] == "<std>/colors.scn" and n["name"] == "tomato" for n in report["names"]))
        self.assertIn("  built in: <std>/colors.scn", run("--check", path).stdout)
        tables = json.loads(run("--language-json").stdout)
        self.assertEqual(sorted(tables["library"]), [f"std/{p.name}" for p in sorted(LIBRARY.glob("*.scn"))])
        self.assertEqual(tables["library"]["std/colors.scn"], (LIBRARY / "colors.scn").read_text())

    def test_a_choice_s_own_word_is_not_taken_for_a_library_name(self):
        # std/colors.scn defines a function `srgb`; `encoding srgb` is still the choice.
        path = self.write("s.scn", 'include "std/colors.scn"\nrender { encoding srgb }\n' + CAMERA)
        result = run("--check", path)
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertIn("8-bit files sRGB-encoded", result.stdout)

    def test_a_file_the_library_lacks_is_an_error_listing_what_it_has(self):
        path = self.write("s.scn", 'include "std/colours.scn"\n' + CAMERA)
        result = run("--check", path)
        self.assertEqual(result.returncode, 1)
        self.assertIn("s.scn:1:9: error: the standard library has no file 'std/colours.scn'; it has std/colors.scn",
                      result.stderr)  # fmt: skip

    def test_srgb_decodes_every_8_bit_value_as_the_standard_says(self):
        prints = "".join(
            "print(" + ", ".join(f"srgb_channel({v})" for v in range(first, first + 8)) + ")\n"
            for first in range(0, 256, 8)
        )
        result = run("--check", self.write("s.scn", 'include "std/colors.scn"\n' + CAMERA + prints))
        decoded = [float(word) for line in self.printed(result) for word in line.split()]
        self.assertEqual(len(decoded), 256)
        for value, got in enumerate(decoded):
            self.assertAlmostEqual(got, srgb_decoded(value), delta=1e-15, msg=value)
        # A named colour is its CSS value decoded: tomato is #ff6347.
        result = run("--check", self.write("t.scn", 'include "std/colors.scn"\n' + CAMERA + "print(tomato)\n"))
        tomato = [float(w) for w in self.printed(result)[0].strip("()").split(", ")]
        self.assertEqual(tomato, [srgb_decoded(255), srgb_decoded(0x63), srgb_decoded(0x47)])

    def test_clear_materials_reflect_f0_and_pass_on_the_rest(self):
        scene = (
            'include "std/materials.scn"\n'
            + CAMERA
            + "".join(
                f"sphere {{ center ({i}, 0, 0) radius 0.4 material {name} }}\n"
                for i, name in enumerate(("glass", "water", "ice", "diamond"))
            )
        )
        dump = json.loads(run("--dump-json", self.write("s.scn", scene)).stdout)
        for sphere, ior in zip(dump["spheres"], (1.5168, 1.333, 1.309, 2.417), strict=True):
            material = sphere["material"]
            f0 = ((ior - 1) / (ior + 1)) ** 2
            self.assertEqual(material["ior"], ior)
            for km, kt in zip(material["km"], material["kt"], strict=True):
                self.assertAlmostEqual(km, f0, delta=1e-15)
                self.assertAlmostEqual(km + kt, 1, delta=1e-15)

    def test_an_include_is_looked_for_beside_then_in_i_folders_then_tracer_path(self):
        for name, where in (("beside", "."), ("first", "one"), ("second", "two"), ("path", "three")):
            self.write(f"{where}/{name}.scn", f'let {name} = "{where}"\n')
        for where in ("one", "two", "three"):  # the same name in each, to see which is taken
            self.write(f"{where}/which.scn", f'let which = "{where}"\n')
        self.write("which.scn", 'let which = "beside"\n')
        scene = self.write(
            "scene/s.scn",
            CAMERA + "".join(f'include "{n}.scn"\n' for n in ("first", "second", "path", "which")) +
            "print(first, second, path, which)\n",
        )  # fmt: skip
        env = dict(os.environ, TRACER_PATH=f"{self.dir / 'nowhere'}:{self.dir / 'three'}")
        result = run("--check", "-I", self.dir / "one", "-I", self.dir / "two", scene, env=env)
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertEqual(self.printed(result), ["one two three one"])
        # Beside the including file comes first.
        self.write("scene/which.scn", 'let which = "beside"\n')
        result = run("--check", "-I", self.dir / "one", "-I", self.dir / "two", scene, env=env)
        self.assertEqual(self.printed(result), ["one two three beside"])
        # Not found anywhere: the folders looked in are named.
        result = run("--check", "-I", self.dir / "one", scene)
        self.assertEqual(result.returncode, 1)
        self.assertIn("cannot include", result.stderr)
        self.assertIn(f"(nor is it in the include folders {self.dir / 'one'})", result.stderr)


if __name__ == "__main__":
    parser = argparse.ArgumentParser()
    parser.add_argument("--tracer", required=True)
    args, rest = parser.parse_known_args()
    TRACER = str(pathlib.Path(args.tracer).resolve())
    unittest.main(argv=[sys.argv[0], *rest])
