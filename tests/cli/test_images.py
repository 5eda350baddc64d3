#!/usr/bin/env python3
"""Image patterns through the command line, in tracer's linear 8-bit PNGs (round(255 v)): 8-bit
files decoded from sRGB to linear, float files (EXR) read as they are, texels across u and up v;
and every bad image file (missing, a folder, truncated, not an image, a header of 100,000 x
100,000 texels, 0 x 0) refused with the scene's file:line:col, a non-zero exit
and no output file; a colour map of a million stops refused with a clear message."""

import argparse
import math
import pathlib
import struct
import subprocess
import sys
import tempfile
import unittest
import zlib

TRACER = ""


def png_bytes(width, height, rows, declared=None):
    """An 8-bit RGB PNG of `rows` (lists of (r, g, b)); `declared` overrides the header's size."""

    def chunk(kind, data):
        body = kind + data
        return struct.pack(">I", len(data)) + body + struct.pack(">I", zlib.crc32(body) & 0xFFFFFFFF)

    w, h = declared or (width, height)
    raw = b"".join(b"\x00" + bytes(c for texel in row for c in texel) for row in rows)
    return (
        b"\x89PNG\r\n\x1a\n"
        + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 2, 0, 0, 0))
        + chunk(b"IDAT", zlib.compress(raw))
        + chunk(b"IEND", b"")
    )


def srgb_decoded(byte):
    """IEC 61966-2-1, written here independently of tracer's table."""
    c = byte / 255
    return c / 12.92 if c <= 0.04045 else ((c + 0.055) / 1.055) ** 2.4


def read_png(path):
    """The pixels of an 8-bit RGB PNG (as tracer writes them), top row first, as (r, g, b) bytes."""
    data = path.read_bytes()
    position, idat, width, height = 8, b"", 0, 0
    while position < len(data):
        (length,) = struct.unpack(">I", data[position : position + 4])
        kind, body = data[position + 4 : position + 8], data[position + 8 : position + 8 + length]
        if kind == b"IHDR":
            width, height = struct.unpack(">II", body[:8])
            assert body[8:10] == b"\x08\x02", "8-bit RGB"
        elif kind == b"IDAT":
            idat += body
        position += 12 + length
    raw, stride, rows, previous = zlib.decompress(idat), 3 * width, [], bytes(3 * width)
    for y in range(height):
        kind, line = raw[y * (stride + 1)], bytearray(raw[y * (stride + 1) + 1 : (y + 1) * (stride + 1)])
        for i in range(stride):  # undo the row's filter (PNG spec, section 9)
            a = line[i - 3] if i >= 3 else 0
            b, c = previous[i], previous[i - 3] if i >= 3 else 0
            if kind == 1:
                line[i] = (line[i] + a) & 255
            elif kind == 2:
                line[i] = (line[i] + b) & 255
            elif kind == 3:
                line[i] = (line[i] + (a + b) // 2) & 255
            elif kind == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append([tuple(line[3 * x : 3 * x + 3]) for x in range(width)])
        previous = bytes(line)
    return rows


def eight_bit(value):
    """round(255 v) of v clamped to 0..1, as tracer's linear files hold it."""
    return int(math.floor(255 * min(1.0, max(0.0, value)) + 0.5))


# A 4 x 4 picture of a square filling the view, lit by its ambient term alone: each pixel is the
# pattern's colour where the pixel's ray meets the square.
SCENE = """render {{ width 4 height 4 }}
camera {{ eye (0, 0, 1) lookat (0, 0, 0) fovy 90 }}
quad {{ corner (-1, -1, 0) edge1 (2, 0, 0) edge2 (0, 2, 0)
  material {{ ka image {{ file "{file}" mapping uv {wrap} }} }} }}
"""


class ImagePatterns(unittest.TestCase):
    def setUp(self):
        self.folder = pathlib.Path(tempfile.mkdtemp())

    def render(self, image_name, wrap="", output="out.png"):
        scene = self.folder / "scene.scn"
        scene.write_text(SCENE.format(file=image_name, wrap=wrap))
        out = self.folder / output
        result = subprocess.run([TRACER, str(scene), "-o", str(out)], capture_output=True, text=True, timeout=60)
        return result, out

    def test_eight_bit_texels_are_decoded_from_srgb(self):
        colour = (200, 64, 3)
        (self.folder / "one.png").write_bytes(png_bytes(1, 1, [[colour]]))
        result, out = self.render("one.png")
        self.assertEqual(result.returncode, 0, result.stderr)
        # 200 is 0.578 linear (147 of 255), not 200 again.
        for row in read_png(out):
            for pixel in row:
                self.assertEqual(pixel, tuple(eight_bit(srgb_decoded(byte)) for byte in colour))

    def test_float_texels_are_read_as_linear_and_unclamped(self):
        # An EXR that tracer itself writes: a scene of background only.
        maker = self.folder / "sky.scn"
        maker.write_text(
            "render { width 2 height 2 background (0.25, 2, 0.5) }\ncamera { eye (0, 0, 1) lookat (0, 0, 0) }\n"
        )
        made = subprocess.run([TRACER, str(maker), "-o", str(self.folder / "sky.exr")], capture_output=True, text=True)
        self.assertEqual(made.returncode, 0, made.stderr)
        result, out = self.render("sky.exr")
        self.assertEqual(result.returncode, 0, result.stderr)
        # Linear: 0.25 stays 64 of 255 (decoded as sRGB it would be 13); 2 is clamped only on output.
        for row in read_png(out):
            for pixel in row:
                self.assertEqual(pixel, (64, 255, 128))

    def test_texels_lie_across_u_and_up_v(self):
        # 2 x 2: top row red, green; bottom row blue, white. The 4 x 4 pixels see u, v in 0..1.
        rows = [[(255, 0, 0), (0, 255, 0)], [(0, 0, 255), (255, 255, 255)]]
        (self.folder / "four.png").write_bytes(png_bytes(2, 2, rows))
        result, out = self.render("four.png", "wrap clamp")
        self.assertEqual(result.returncode, 0, result.stderr)
        pixels = read_png(out)
        self.assertEqual(pixels[0][0], (255, 0, 0))  # top left: u 1/8, v 7/8, clamped
        self.assertEqual(pixels[0][3], (0, 255, 0))
        self.assertEqual(pixels[3][0], (0, 0, 255))
        self.assertEqual(pixels[3][3], (255, 255, 255))
        # Pixel (1, 1) is at u = 3/8, v = 5/8: a quarter of the way from each texel center.
        expected = [
            0.75 * 0.75 * r + 0.25 * 0.75 * g + 0.75 * 0.25 * b + 0.25 * 0.25 * w
            for r, g, b, w in zip((1, 0, 0), (0, 1, 0), (0, 0, 1), (1, 1, 1), strict=True)
        ]
        self.assertEqual(pixels[1][1], tuple(eight_bit(v) for v in expected))

    def assert_refused(self, image_name, *fragments):
        result, out = self.render(image_name)
        self.assertNotEqual(result.returncode, 0)
        self.assertFalse(out.exists(), "no output file on an error")
        self.assertIn("scene.scn:4:", result.stderr)  # where the file is named
        self.assertIn("cannot read image file", result.stderr)
        self.assertNotIn("overrides", result.stderr)  # one message, about the image
        self.assertNotIn("Traceback", result.stderr)
        # The message alone: no line of libpng's own, the source line right after it.
        self.assertNotIn("libpng", result.stderr)
        lines = result.stderr.splitlines()
        at = next(i for i, line in enumerate(lines) if "cannot read image file" in line)
        self.assertIn("file", lines[at + 1], result.stderr)
        for fragment in fragments:
            self.assertIn(fragment, result.stderr)
        return result.stderr

    def test_bad_image_files_are_errors_at_their_name(self):
        self.assert_refused("missing.png", "no such file")
        (self.folder / "folder.png").mkdir()
        self.assert_refused("folder.png")
        good = png_bytes(4, 4, [[(1, 2, 3)] * 4] * 4)
        (self.folder / "truncated.png").write_bytes(good[:40])
        self.assert_refused("truncated.png")
        (self.folder / "text.jpg").write_text("not a picture at all\n")
        self.assert_refused("text.jpg")
        (self.folder / "empty.png").write_bytes(b"")
        self.assert_refused("empty.png")

    def test_absurd_headers_are_refused_before_reading(self):
        (self.folder / "huge.png").write_bytes(png_bytes(1, 1, [[(0, 0, 0)]], declared=(100000, 100000)))
        self.assert_refused("huge.png", "100000 x 100000 texels, more than tracer holds")
        (self.folder / "none.png").write_bytes(png_bytes(1, 1, [[(0, 0, 0)]], declared=(0, 0)))
        self.assert_refused("none.png")

    def test_a_million_stops_are_refused(self):
        stops = ", ".join(["[0.5, 1]"] * 1_000_000)
        scene = self.folder / "stops.scn"
        scene.write_text(
            "camera { eye (0, 0, 7) lookat (0, 0, 0) }\n"
            f"sphere {{ center (0, 0, 0) radius 1 material {{ kd gradient {{ colors [{stops}] }} }} }}\n"
        )
        result = subprocess.run([TRACER, "--check", str(scene)], capture_output=True, text=True, timeout=60)
        self.assertNotEqual(result.returncode, 0)
        self.assertIn("stops.scn:2:", result.stderr)
        self.assertIn("error:", result.stderr)


if __name__ == "__main__":
    parser = argparse.ArgumentParser()
    parser.add_argument("--tracer", required=True)
    args, rest = parser.parse_known_args()
    TRACER = str(pathlib.Path(args.tracer).resolve())
    unittest.main(argv=[sys.argv[0], *rest])
