"""tracer's cones, cylinders and discs for Mitsuba 3 (used by xcheck.convert).

Mitsuba has no cone, and its open `cylinder` shows shadow acne in float32 (black specks on a
lit cylinder where tracer has none): the side of every cone and cylinder becomes an OBJ beside
the XML, with enough sides that its outline is within MAX_ERROR_PIXELS of the true one where the
eye sees it, its vertex normals the true cone's. Discs and caps are Mitsuba `disk`s.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

MAX_ERROR_PIXELS = 0.001
MIN_SIDES, MAX_SIDES = 16, 4096
RING_RATIO = 1.5
APEX_FRACTION = 1e-3


def _sub(a: Sequence[float], b: Sequence[float]) -> list[float]:
    return [x - y for x, y in zip(a, b, strict=True)]


def _cross(a: Sequence[float], b: Sequence[float]) -> list[float]:
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def _normalize(a: Sequence[float]) -> list[float]:
    length = math.sqrt(sum(x * x for x in a))
    return [x / length for x in a]


def frame(normal: Sequence[float]) -> tuple[list[float], list[float], list[float]]:
    """Unit u, v, n with u x v = n: the directions that +x, +y and +z of a Mitsuba disk map to."""
    n = _normalize(normal)
    helper = [1.0, 0.0, 0.0] if abs(n[0]) < 0.9 else [0.0, 1.0, 0.0]
    u = _normalize(_cross(helper, n))
    return u, _cross(n, u), n


def disk_matrix(center: Sequence[float], normal: Sequence[float], radius: float) -> list[list[float]]:
    """Rows of the 4 x 4 to_world of Mitsuba's unit disk (radius 1 at the origin, facing +z)."""
    u, v, n = frame(normal)
    return [[radius * u[i], radius * v[i], n[i], center[i]] for i in range(3)] + [[0.0, 0.0, 0.0, 1.0]]


def disks_of(scene: dict) -> list[tuple[str, list[list[float]], dict]]:
    """(id, to_world rows, material) of every Mitsuba disk: the scene's discs, then the caps of
    its capped cones and cylinders (a cap of radius 0 is a point: none)."""
    out = []
    for index, disc in enumerate(scene.get("discs", [])):
        out.append((f"disc{index}", disk_matrix(disc["center"], disc["normal"], disc["radius"]), disc["material"]))
    for index, cone in enumerate(scene.get("cones", [])):
        if not cone["caps"]:
            continue
        axis = _sub(cone["top"], cone["base"])
        ends = ((cone["base"], [-a for a in axis], cone["base_radius"]), (cone["top"], axis, cone["top_radius"]))
        for end, (center, outward, radius) in enumerate(ends):
            if radius > 0:
                out.append((f"cone{index}cap{end}", disk_matrix(center, outward, radius), cone["material"]))
    return out


def sides_for(cone: dict, eye: Sequence[float], pixel_angle: float) -> int:
    """Sides for the OBJ of a cone so that its outline departs from the true cone by at most
    MAX_ERROR_PIXELS where the eye sees it (r (1 - cos(pi / N)) ~ r pi^2 / (2 N^2))."""
    radius = max(cone["base_radius"], cone["top_radius"])
    centre = [(a + b) / 2 for a, b in zip(cone["base"], cone["top"], strict=True)]
    reach = math.dist(cone["base"], cone["top"]) / 2 + radius
    distance = max(math.dist(centre, eye) - reach, 1e-3 * reach)
    sides = math.pi * math.sqrt(radius / (2 * MAX_ERROR_PIXELS * distance * pixel_angle))
    return int(min(max(math.ceil(sides), MIN_SIDES), MAX_SIDES))


def ring_radii(r0: float, r1: float) -> list[float]:
    """The radii of the rings of a cone's OBJ from one end (r0) to the other (r1): consecutive
    ones within RING_RATIO of each other, so that the vertex normals, interpolated linearly
    across a triangle, stay within a small part of a side's angle of the true ones (between two
    rings of one radius the interpolation is exact; a triangle reaching the apex of a pointed
    cone bends its normals by up to half a side's angle, which a mirror shows). A pointed end's
    last ring is at APEX_FRACTION of the other radius, then the apex."""
    wide, narrow = max(r0, r1), min(r0, r1)
    smallest = max(narrow, APEX_FRACTION * wide)
    steps = max(1, math.ceil(math.log(wide / smallest) / math.log(RING_RATIO))) if smallest < wide else 1
    radii = [wide * (smallest / wide) ** (i / steps) for i in range(steps + 1)]
    if narrow < smallest:
        radii.append(narrow)
    return radii if r0 >= r1 else radii[::-1]


def cone_obj(cone: dict, sides: int) -> str:
    """The side of a cone as an OBJ: rings of `sides` vertices (ring_radii) joined by quads (two
    triangles each), each vertex with the true cone's outward normal (caps: disks_of)."""
    base, top = cone["base"], cone["top"]
    axis = _sub(top, base)
    height = math.sqrt(sum(a * a for a in axis))
    u, v, w = frame(axis)
    r0, r1 = cone["base_radius"], cone["top_radius"]
    slope = (r1 - r0) / height
    radii = ring_radii(r0, r1)
    # Heights: linear in the radius on a cone, evenly spaced rings on a cylinder.
    heights = [height * i / (len(radii) - 1) if r0 == r1 else (r - r0) / slope for i, r in enumerate(radii)]
    heights[0], heights[-1] = 0.0, height
    lines = [f"# cone side, {sides} sides, {len(radii)} rings (tools/tracer_tools/xcheck/round_shapes.py)"]
    for k in range(sides):
        angle = 2 * math.pi * k / sides
        across = [math.cos(angle) * u[i] + math.sin(angle) * v[i] for i in range(3)]
        normal = _normalize([across[i] - slope * w[i] for i in range(3)])
        lines.append("vn " + " ".join(repr(x) for x in normal))
    for h, radius in zip(heights, radii, strict=True):
        for k in range(sides):
            angle = 2 * math.pi * k / sides
            across = [math.cos(angle) * u[i] + math.sin(angle) * v[i] for i in range(3)]
            lines.append("v " + " ".join(repr(base[i] + h * w[i] + radius * across[i]) for i in range(3)))
    for ring in range(len(radii) - 1):
        for k in range(sides):
            following = (k + 1) % sides
            a, c = ring * sides + k + 1, ring * sides + following + 1  # this ring (1-based)
            b, d = a + sides, c + sides  # the next ring
            na, nc = k + 1, following + 1
            if radii[ring] > 0:
                lines.append(f"f {a}//{na} {c}//{nc} {d}//{nc}")
            if radii[ring + 1] > 0:
                lines.append(f"f {a}//{na} {d}//{nc} {b}//{na}")
    return "\n".join(lines) + "\n"
