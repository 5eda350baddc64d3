#!/usr/bin/env python3
"""The image files tracer writes itself (PNG through libpng, binary PPM): the same pixels as
OpenImageIO's encoder gives (a BMP, linear and sRGB), the PNG marked sRGB exactly when it is
sRGB-encoded, and written without loading OpenImageIO's module (the dynamic loader's own log)."""

import argparse
import os
import pathlib
import struct
import subprocess
import sys
import tempfile
import unittest

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
from test_images import read_png  # noqa: E402

TRACER = ""

# Colours on both sides of the sRGB curve's bend, and values past 1 (clamped).
SCENE = """render { width 7 height 5 }
camera { eye (0, 0, 3) lookat (0, 0, 0) fovy 50 }
light { position (2, 3, 4) color (1.5, 1.2, 1) }
sphere { center (0, 0, 0) radius 1 material { ka (0.002, 0.02, 0.2) kd (0.9, 0.4, 0.05) ks 0.5 n 20 } }
"""


def read_ppm(path):
    """The pixels of a binary 8-bit PPM (P6), top row first, as (r, g, b) tuples."""
    data = path.read_bytes()
    fields, position = [], 0
    while len(fields) < 4:  # magic, width, height, maximum: separated by whitespace
        while data[position : position + 1].isspace():
            position += 1
        start = position
        while not data[position : position + 1].isspace():
            position += 1
        fields.append(data[start:position])
    assert fields[0] == b"P6" and fields[3] == b"255"
    width, height = int(fields[1]), int(fields[2])
    pixels = data[position + 1 :]
    assert len(pixels) == 3 * width * height
    return [[tuple(pixels[3 * (y * width + x) : 3 * (y * width + x) + 3]) for x in range(width)] for y in range(height)]


def read_bmp(path):
    """The pixels of a 24-bit BMP (rows bottom-up, BGR, each padded to 4 bytes), top row first."""
    data = path.read_bytes()
    offset = struct.unpack("<I", data[10:14])[0]
    width, height = struct.unpack("<ii", data[18:26])
    assert struct.unpack("<H", data[28:30])[0] == 24
    stride = (3 * width + 3) // 4 * 4
    rows = []
    for y in range(abs(height)):
        row = data[offset + y * stride : offset + y * stride + 3 * width]
        rows.append([(row[3 * x + 2], row[3 * x + 1], row[3 * x]) for x in range(width)])
    return rows[::-1] if height > 0 else rows


def chunk_kinds(path):
    """The kinds of a PNG's chunks, in order."""
    data, position, kinds = path.read_bytes(), 8, []
    while position < len(data):
        (length,) = struct.unpack(">I", data[position : position + 4])
        kinds.append(data[position + 4 : position + 8].decode())
        position += 12 + length
    return kinds


class OutputFiles(unittest.TestCase):
    def setUp(self):
        self.folder = pathlib.Path(tempfile.mkdtemp())
        self.scene = self.folder / "scene.scn"
        self.scene.write_text(SCENE)

    def render(self, name, *options, env=None):
        out = self.folder / name
        result = subprocess.run(
            [TRACER, str(self.scene), "-o", str(out), "-q", *options],
            capture_output=True,
            text=True,
            timeout=60,
            env=env,
        )
        self.assertEqual(result.returncode, 0, result.stderr)
        return out, result

    def test_png_and_ppm_hold_the_pixels_openimageio_writes(self):
        for encoding in ("linear", "srgb"):
            with self.subTest(encoding=encoding):
                png, _ = self.render(f"{encoding}.png", "--encoding", encoding)
                ppm, _ = self.render(f"{encoding}.ppm", "--encoding", encoding)
                bmp, _ = self.render(f"{encoding}.bmp", "--encoding", encoding)
                expected = read_bmp(bmp)
                self.assertEqual(len(expected), 5)
                self.assertEqual(read_png(png), expected)
                self.assertEqual(read_ppm(ppm), expected)
                # Not one colour: the test sees the curve and the clamp.
                self.assertGreater(len({p for row in expected for p in row}), 5)

    def test_a_png_is_marked_srgb_only_when_it_is(self):
        linear, _ = self.render("linear.png")
        srgb, _ = self.render("srgb.png", "--encoding", "srgb")
        self.assertEqual(set(chunk_kinds(linear)), {"IHDR", "IDAT", "IEND"})  # no colour chunk: as written
        self.assertIn("sRGB", chunk_kinds(srgb))
        self.assertLess(chunk_kinds(srgb).index("sRGB"), chunk_kinds(srgb).index("IDAT"))

    def test_png_and_ppm_are_written_without_openimageio(self):
        env = dict(os.environ, LD_DEBUG="libs")
        for name in ("plain.png", "plain.ppm", "plain.bmp"):
            with self.subTest(name=name):
                _, result = self.render(name, env=env)
                loaded = "libOpenImageIO" in result.stderr
                # The loader's log names the library when it is loaded (the BMP shows the test can see it).
                self.assertEqual(loaded, name.endswith(".bmp"), name)


if __name__ == "__main__":
    parser = argparse.ArgumentParser()
    parser.add_argument("--tracer", required=True)
    args, rest = parser.parse_known_args()
    TRACER = str(pathlib.Path(args.tracer).resolve())
    unittest.main(argv=[sys.argv[0], *rest])
