"""Writes the many-object scenes: a field of spheres, or a grid of instanced bunnies.

    tools/make-scene many-objects spheres [--count N] [-o FILE]
    tools/make-scene many-objects bunnies [--count N] [-o FILE]

spheres: N spheres (default 4,096) on a square grid over a floor plane, radii and colours drawn
from a fixed seed, about one in eight a mirror, with three large mirror spheres behind them;
the camera frames the whole grid at any N. bunnies: N Stanford bunnies (default 64), each a
`mesh` block naming the same OBJ file (read and built once), turned, scaled (some squashed
non-uniformly) and coloured differently, on a floor with two mirror spheres. The same N
always gives the same file. scenes/many_spheres.scn and scenes/bunnies.scn are the defaults;
tools/bench many writes other sizes.
"""

from __future__ import annotations

import argparse
import math
import pathlib
import random
import sys

from tracer_tools import ROOT, option_types

PALETTE = """\
material red    { ka 0.1  kd (0.85, 0.2, 0.15)  ks 0.5  n 30 }
material green  { ka 0.1  kd (0.2, 0.75, 0.3)   ks 0.5  n 30 }
material blue   { ka 0.1  kd (0.15, 0.3, 0.85)  ks 0.5  n 30 }
material gold   { ka 0.1  kd (0.85, 0.65, 0.2)  ks 0.8  n 60 }
material white  { ka 0.1  kd 0.8  ks 0.3  n 20 }
material chrome { ka 0.02  kd 0.05  ks 0.5  n 80  km 0.7 }
material mirror { km 0.9 }
material floor  { ka 0.1  kd 0.6 }
"""
COLOURS = ["red", "green", "blue", "gold", "white"]


def scene_text(lines: list[str]) -> str:
    """The scene's lines as text, its "PALETTE" line replaced by the materials it uses."""
    text = "\n".join(lines) + "\n"
    return text.replace("PALETTE\n", used_materials(text))


def used_materials(text: str) -> str:
    """PALETTE's lines for the materials `text` uses (an unused material is a warning)."""
    return (
        "\n".join(
            line
            for line in PALETTE.splitlines()
            if f"material {line.split()[1]} " in text or f"material {line.split()[1]} }}" in text
        )
        + "\n"
    )


def spheres(count: int) -> str:
    rng = random.Random(count)
    side = math.ceil(math.sqrt(count))
    half = side / 2
    lines = [
        f"# {count:,} spheres on a {side} x {side} grid over a floor, about one in eight a mirror, and",
        "# three large mirror spheres behind them. Written by tools/make-scene many-objects spheres"
        f" --count {count}.",
        "",
        "render { width 800  height 600  max_depth 4 }",
        "",
        f"camera {{ eye (0, {0.42 * side + 2:.4g}, {0.62 * side + 3:.4g})  lookat (0, 0, {-0.12 * side:.4g})"
        "  up (0, 1, 0)  fovy 50 }",
        "",
        "PALETTE",
        "plane { point (0, 0, 0)  normal (0, 1, 0)  material floor }",
        "",
    ]
    for x, r in ((-0.45, 0.18), (0.0, 0.22), (0.45, 0.18)):
        radius = r * side
        lines.append(
            f"sphere {{ center ({x * side:.4f}, {radius:.4f}, {-half - radius - 1:.4f})"
            f"  radius {radius:.4f}  material mirror }}"
        )
    for i in range(count):
        gx, gz = i % side, i // side
        radius = 0.25 + 0.2 * rng.random()
        x = gx - half + 0.5 + (rng.random() - 0.5) * (0.9 - 2 * radius)
        z = gz - half + 0.5 + (rng.random() - 0.5) * (0.9 - 2 * radius)
        material = "chrome" if rng.random() < 0.125 else rng.choice(COLOURS)
        lines.append(f"sphere {{ center ({x:.4f}, {radius:.4f}, {z:.4f})  radius {radius:.4f}  material {material} }}")
    lines += [
        "",
        f"light {{ position ({-0.6 * side:.4g}, {side + 5:.4g}, {0.8 * side:.4g})  color 0.6 }}",
        f"light {{ position ({0.7 * side:.4g}, {0.5 * side + 3:.4g}, {0.2 * side:.4g})  color 0.35 }}",
    ]
    return scene_text(lines)


def bunnies(count: int, obj: str | pathlib.Path) -> str:
    rng = random.Random(count)
    side = math.ceil(math.sqrt(count))
    pitch = 1.6
    half = side * pitch / 2
    lines = [
        f"# {count:,} Stanford bunnies: one mesh file, read and built once, placed by {count:,} mesh blocks",
        "# (turned, scaled, some squashed, coloured), on a floor with two mirror spheres.",
        f"# Written by tools/make-scene many-objects bunnies --count {count}.",
        "",
        "render { width 800  height 600  max_depth 4 }",
        "",
        f"camera {{ eye (0, {0.75 * half + 2.5:.4g}, {1.35 * half + 3.5:.4g})  lookat (0, 0, {-0.3 * half:.4g})"
        "  up (0, 1, 0)  fovy 45 }",
        "",
        "PALETTE",
        "plane { point (0, 0, 0)  normal (0, 1, 0)  material floor }",
        f"sphere {{ center ({-0.4 * half:.4f}, {0.35 * half:.4f}, {-half - 0.4 * half:.4f})  radius {0.35 * half:.4f}"
        "  material mirror }",
        f"sphere {{ center ({0.45 * half:.4f}, {0.25 * half:.4f}, {-half - 0.3 * half:.4f})  radius {0.25 * half:.4f}"
        "  material mirror }",
        "",
    ]
    for i in range(count):
        gx, gz = i % side, i // side
        size = 0.09 + 0.04 * rng.random()
        squash = rng.random() < 0.25
        scale = f"({size * 1.3:.4f}, {size * 0.75:.4f}, {size:.4f})" if squash else f"{size:.4f}"
        angle = 360 * rng.random() - 180
        # The raw bunny's feet are at y = 0 (its lowest vertex at -0.00315 units): lift it a hair.
        height = 0.0032 * (size * 0.75 if squash else size) * 1.01
        x = gx * pitch - half + pitch / 2 + 0.3 * (rng.random() - 0.5)
        z = gz * pitch - half + pitch / 2 + 0.3 * (rng.random() - 0.5)
        material = "chrome" if rng.random() < 0.125 else rng.choice(COLOURS)
        lines.append(
            f'mesh {{ file "{obj}"  scale {scale}  rotate {{ axis (0, 1, 0)  angle {angle:.2f} }}'
            f"  translate ({x:.4f}, {height:.5f}, {z:.4f})  material {material} }}"
        )
    lines += [
        "",
        f"light {{ position ({-0.5 * half:.4g}, {half + 6:.4g}, {half + 4:.4g})  color 0.6 }}",
        f"light {{ position ({0.8 * half + 2:.4g}, {0.4 * half + 3:.4g}, {0.3 * half:.4g})  color 0.35 }}",
    ]
    return scene_text(lines)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("kind", choices=["spheres", "bunnies"])
    parser.add_argument(
        "--count",
        type=option_types.whole_number(1, 1_000_000),
        default=None,
        help="objects (default 4096 spheres, 64 bunnies)",
    )
    parser.add_argument("-o", "--output", type=option_types.output_file, default=None)
    parser.add_argument(
        "--obj",
        type=option_types.free_text,
        default="meshes/bunny.obj",
        help="the bunnies' OBJ file as the scene names it",
    )
    args = parser.parse_args()
    if args.kind == "spheres":
        count = args.count or 4096
        text, default = spheres(count), ROOT / "scenes" / "many_spheres.scn"
    else:
        count = args.count or 64
        text, default = bunnies(count, args.obj), ROOT / "scenes" / "bunnies.scn"
    if count < 1:
        sys.exit("tools/make-scene many-objects: --count must be at least 1")
    output = args.output or default
    output.write_text(text)
    print(f"{output}: {count} {args.kind}")


if __name__ == "__main__":
    main()
