#!/usr/bin/env python3
"""noise() and turbulence() (issue 54's noise, shared with the patterns) against an independent
implementation of Perlin's improved noise, written here from the definition in src/scene/noise.h
(itself the SIGGRAPH 2002 reference): the same values at random points, negative and far ones
included, through the language's print()."""

import argparse
import math
import pathlib
import random
import subprocess
import sys
import tempfile
import unittest

TRACER = ""

# Perlin's permutation, as published with the 2002 reference implementation.
PERMUTATION = [
    151, 160, 137, 91, 90, 15, 131, 13, 201, 95, 96, 53, 194, 233, 7, 225, 140, 36, 103, 30, 69, 142, 8, 99, 37, 240,
    21, 10, 23, 190, 6, 148, 247, 120, 234, 75, 0, 26, 197, 62, 94, 252, 219, 203, 117, 35, 11, 32, 57, 177, 33, 88,
    237, 149, 56, 87, 174, 20, 125, 136, 171, 168, 68, 175, 74, 165, 71, 134, 139, 48, 27, 166, 77, 146, 158, 231,
    83, 111, 229, 122, 60, 211, 133, 230, 220, 105, 92, 41, 55, 46, 245, 40, 244, 102, 143, 54, 65, 25, 63, 161, 1,
    216, 80, 73, 209, 76, 132, 187, 208, 89, 18, 169, 200, 196, 135, 130, 116, 188, 159, 86, 164, 100, 109, 198,
    173, 186, 3, 64, 52, 217, 226, 250, 124, 123, 5, 202, 38, 147, 118, 126, 255, 82, 85, 212, 207, 206, 59, 227, 47,
    16, 58, 17, 182, 189, 28, 42, 223, 183, 170, 213, 119, 248, 152, 2, 44, 154, 163, 70, 221, 153, 101, 155, 167,
    43, 172, 9, 129, 22, 39, 253, 19, 98, 108, 110, 79, 113, 224, 232, 178, 185, 112, 104, 218, 246, 97, 228, 251,
    34, 242, 193, 238, 210, 144, 12, 191, 179, 162, 241, 81, 51, 145, 235, 249, 14, 239, 107, 49, 192, 214, 31, 181,
    199, 106, 157, 184, 84, 204, 176, 115, 121, 50, 45, 127, 4, 150, 254, 138, 236, 205, 93, 222, 114, 67, 29, 24,
    72, 243, 141, 128, 195, 78, 66, 215, 61, 156, 180,
]  # fmt: skip
P = PERMUTATION * 2


def fade(t):
    return t * t * t * (t * (t * 6 - 15) + 10)


def lerp(t, a, b):
    return a + t * (b - a)


def grad(hash_, x, y, z):
    h = hash_ & 15
    u = x if h < 8 else y
    v = y if h < 4 else (x if h in (12, 14) else z)
    return (u if h & 1 == 0 else -u) + (v if h & 2 == 0 else -v)


def noise(x, y, z):
    X, Y, Z = (math.floor(c) & 255 for c in (x, y, z))
    x, y, z = x - math.floor(x), y - math.floor(y), z - math.floor(z)
    u, v, w = fade(x), fade(y), fade(z)
    A = P[X] + Y
    AA, AB = P[A] + Z, P[A + 1] + Z
    B = P[X + 1] + Y
    BA, BB = P[B] + Z, P[B + 1] + Z
    return lerp(
        w,
        lerp(v, lerp(u, grad(P[AA], x, y, z), grad(P[BA], x - 1, y, z)),
             lerp(u, grad(P[AB], x, y - 1, z), grad(P[BB], x - 1, y - 1, z))),
        lerp(v, lerp(u, grad(P[AA + 1], x, y, z - 1), grad(P[BA + 1], x - 1, y, z - 1)),
             lerp(u, grad(P[AB + 1], x, y - 1, z - 1), grad(P[BB + 1], x - 1, y - 1, z - 1))),
    )  # fmt: skip


def turbulence(x, y, z, octaves):
    return sum(abs(noise(x * 2**i, y * 2**i, z * 2**i)) / 2**i for i in range(octaves))


class Noise(unittest.TestCase):
    def printed(self, calls):
        """The numbers `print(CALL)` writes for each call, in order."""
        with tempfile.TemporaryDirectory() as folder:
            scene = pathlib.Path(folder) / "noise.scn"
            scene.write_text(
                "camera { eye (0, 0, 5) lookat (0, 0, 0) }\nlight { position (0, 5, 5) }\n"
                + "".join(f"print({call})\n" for call in calls)
            )
            result = subprocess.run([TRACER, "--check", scene], capture_output=True, text=True, timeout=60)
        self.assertEqual(result.returncode, 0, result.stderr)
        return [float(line.split("print: ")[1]) for line in result.stderr.splitlines() if "print: " in line]

    def test_the_permutation_is_one(self):
        self.assertEqual(sorted(PERMUTATION), list(range(256)))

    def test_noise_is_the_reference_at_random_points(self):
        rng = random.Random(54)
        points = [(rng.uniform(-4, 4), rng.uniform(-4, 4), rng.uniform(-4, 4)) for _ in range(300)]
        points += [(rng.uniform(-1e6, 1e6), rng.uniform(-300, 300), rng.uniform(-1e3, 1e3)) for _ in range(100)]
        points += [(1, 2, 3), (-256, 0, 511), (0.5, 0.5, 0.5)]
        got = self.printed(f"noise(({x!r}, {y!r}, {z!r}))" for x, y, z in points)
        self.assertEqual(len(got), len(points))
        for point, value in zip(points, got, strict=True):
            self.assertAlmostEqual(value, noise(*point), delta=1e-12, msg=point)
        self.assertEqual(got[-3:-1], [0.0, 0.0])  # the lattice
        self.assertTrue(all(-1.1 < v < 1.1 for v in got))

    def test_turbulence_sums_octaves_as_defined(self):
        rng = random.Random(1985)
        cases = [((rng.uniform(-9, 9), rng.uniform(-9, 9), rng.uniform(-9, 9)), rng.randint(1, 12)) for _ in range(100)]
        got = self.printed(f"turbulence(({x!r}, {y!r}, {z!r}), {n})" for (x, y, z), n in cases)
        for ((x, y, z), n), value in zip(cases, got, strict=True):
            self.assertAlmostEqual(value, turbulence(x, y, z, n), delta=1e-12)
            self.assertTrue(0 <= value < 2)


if __name__ == "__main__":
    parser = argparse.ArgumentParser()
    parser.add_argument("--tracer", required=True)
    args, rest = parser.parse_known_args()
    TRACER = str(pathlib.Path(args.tracer).resolve())
    unittest.main(argv=[sys.argv[0], *rest])
