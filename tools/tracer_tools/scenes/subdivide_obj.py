"""1-to-4 midpoint subdivision of a triangle OBJ, for BVH scaling runs.

    tools/make-scene subdivide-obj scenes/meshes/bunny.obj out/bench/bunny_sub2.obj --passes 2

Each pass splits every triangle (a, b, c) into (a, ab, ca), (ab, b, bc), (ca, bc, c) and
(ab, bc, ca), where ab is the midpoint of edge a-b, shared by both triangles on that edge, so
a closed mesh stays closed and the surface does not change. Orientation is kept. Reads only
`v` and triangular `f` lines (as tools/make-scene bunny-obj writes them); the bunny's 3,674
triangles become 14,696 / 58,784 / 235,136 / 940,544 after 1 / 2 / 3 / 4 passes.
"""

from __future__ import annotations

import argparse
import pathlib
import sys

from tracer_tools import option_types


def read_obj(path: pathlib.Path) -> tuple[list, list]:
    vertices, faces = [], []
    for line in option_types.read_text_file(path, 1 << 30).splitlines():
        parts = line.split()
        if not parts:
            continue
        if parts[0] == "v":
            vertices.append(tuple(float(x) for x in parts[1:4]))
        elif parts[0] == "f":
            corners = [int(p.split("/")[0]) for p in parts[1:]]
            if len(corners) != 3:
                sys.exit(f"{path}: only triangles are supported, found a face with {len(corners)} corners")
            faces.append(tuple(c - 1 if c > 0 else len(vertices) + c for c in corners))
    return vertices, faces


def subdivide(vertices: list, faces: list) -> tuple[list, list]:
    vertices = list(vertices)
    midpoints = {}

    def midpoint(a: int, b: int) -> int:
        key = (a, b) if a < b else (b, a)
        if key not in midpoints:
            pa, pb = vertices[a], vertices[b]
            vertices.append(tuple((x + y) / 2 for x, y in zip(pa, pb, strict=False)))
            midpoints[key] = len(vertices) - 1
        return midpoints[key]

    finer = []
    for a, b, c in faces:
        ab, bc, ca = midpoint(a, b), midpoint(b, c), midpoint(c, a)
        finer += [(a, ab, ca), (ab, b, bc), (ca, bc, c), (ab, bc, ca)]
    return vertices, finer


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("input", type=option_types.existing_file)
    parser.add_argument("output", type=option_types.output_file)
    parser.add_argument("--passes", type=option_types.whole_number(1, 1_000_000), default=1)
    args = parser.parse_args()
    vertices, faces = read_obj(args.input)
    for _ in range(args.passes):
        vertices, faces = subdivide(vertices, faces)
    args.output.parent.mkdir(parents=True, exist_ok=True)
    with args.output.open("w") as out:
        out.write(
            f"# {args.input.name} after {args.passes} pass(es) of 1-to-4 midpoint subdivision "
            f"(tools/make-scene subdivide-obj): {len(vertices)} vertices, {len(faces)} triangles\n"
        )
        out.writelines(f"v {x!r} {y!r} {z!r}\n" for x, y, z in vertices)
        out.writelines(f"f {a + 1} {b + 1} {c + 1}\n" for a, b, c in faces)
    print(f"{args.output}: {len(faces)} triangles")
    return 0


if __name__ == "__main__":
    sys.exit(main())
