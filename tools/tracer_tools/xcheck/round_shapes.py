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


def cone_obj(cone: dict, sides: int) -> str:
    """The side of a cone as an OBJ: `sides` quads (two triangles each)
    between its two rims, each vertex with the true cone's outward normal (caps: disks_of)."""
    base, top = cone["base"], cone["top"]
    axis = _sub(top, base)
    height = math.sqrt(sum(a * a for a in axis))
    u, v, w = frame(axis)
    r0, r1 = cone["base_radius"], cone["top_radius"]
    slope = (r1 - r0) / height
    lines = [f"# cone side, {sides} sides (tools/tracer_tools/xcheck/round_shapes.py)"]
    for k in range(sides):
        angle = 2 * math.pi * k / sides
        across = [math.cos(angle) * u[i] + math.sin(angle) * v[i] for i in range(3)]
        for centre, radius in ((base, r0), (top, r1)):
            lines.append("v " + " ".join(repr(centre[i] + radius * across[i]) for i in range(3)))
        normal = _normalize([across[i] - slope * w[i] for i in range(3)])
        lines.append("vn " + " ".join(repr(x) for x in normal))
    for k in range(sides):
        a, b = 2 * k + 1, 2 * k + 2  # this angle's base and top vertices (1-based)
        c, d = 2 * ((k + 1) % sides) + 1, 2 * ((k + 1) % sides) + 2
        na, nc = k + 1, (k + 1) % sides + 1
        lines.append(f"f {a}//{na} {c}//{nc} {d}//{nc}")
        lines.append(f"f {a}//{na} {d}//{nc} {b}//{na}")
    return "\n".join(lines) + "\n"
