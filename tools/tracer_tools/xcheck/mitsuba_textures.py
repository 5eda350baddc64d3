"""tracer's patterns (the JSON of `tracer --dump-json`) as Mitsuba 3 textures, where Mitsuba can
express them: a checker as `checkerboard` and an image as `bitmap`, both looked up at the
surface's (u, v). Mitsuba's checkerboard is the checker of half-unit squares over its to_uv
coordinates (color0 where both fractions are on the same side of 0.5), so a tracer checker
becomes one when its cells' parity varies with two coordinates that are affine in the shape's
(u, v): any checker in `uv` mapping, and a solid one on a quad or a plane whose third
coordinate is constant across it. A sphere's (u, v) are Mitsuba's, turned (sphere_to_world).
Mitsuba's bitmap has its (0, 0) at the picture's top left, and its OBJ loader turns each `vt`'s
v into 1 - v; both are undone by each texture's to_uv. Other patterns (noise, colour maps, other
mappings; boxes, cones and discs, whose (u, v) Mitsuba lays otherwise) are refused with a
reason.
"""

from __future__ import annotations

import numpy as np

from . import ToolError

CHECKER_NUDGE = 1e-6  # as src/scene/pattern.cpp's kCheckerNudge

# A map from Mitsuba's (u, v) of a shape to points: a 4 x 3 matrix taking (u, v, 1) to (x, y, z, 1).
SurfaceMap = np.ndarray


def _affine4(rows: list) -> np.ndarray:
    return np.array([*rows, [0, 0, 0, 1]], dtype=np.float64)


def uv_map_of_obj() -> SurfaceMap:
    """Mitsuba's (u, v) of an OBJ mesh -> tracer's (u, v, 0): v was turned into 1 - v."""
    return np.array([[1, 0, 0], [0, -1, 1], [0, 0, 0], [0, 0, 1]], dtype=np.float64)


def uv_map_of_rectangle() -> SurfaceMap:
    """Mitsuba's (u, v) of a rectangle (a quad) are tracer's (u, v, 0) already."""
    return np.array([[1, 0, 0], [0, 1, 0], [0, 0, 0], [0, 0, 1]], dtype=np.float64)


def uv_map_of_sphere() -> SurfaceMap:
    """Mitsuba's (u, v) of a sphere written by sphere_to_world -> tracer's (u, v, 0): u is the
    same, v turned (Mitsuba's 0 is the north pole, tracer's the south)."""
    return uv_map_of_obj()


# Mitsuba's sphere in its own coordinates has u = atan2(y, x) / 2 pi (0 towards +x, rising
# towards +y) and v = the angle from +z / pi; tracer's sphere (docs/guide/patterns.md) has u = 0
# towards -z rising towards -x, and its north pole at +y. Mitsuba's x, y, z are tracer's -z, -x, y.
_SPHERE_TURN = np.array([[0, -1, 0], [0, 0, 1], [-1, 0, 0]], dtype=np.float64)


def sphere_to_world(sphere: dict) -> np.ndarray:
    """The 4 x 4 to_world of a Mitsuba sphere that lays (u, v) as tracer's: its centre and
    radius, turned as the sphere's own coordinates are (its material's to_object)."""
    to_object = np.array(sphere["material"].get("to_object", np.eye(3, 4)), dtype=np.float64)[:, :3]
    placed = np.linalg.inv(to_object)
    if np.linalg.det(placed) < 0:
        raise ToolError("a mirrored sphere's (u, v): Mitsuba's sphere has no mirrored placement")
    turn = placed / np.linalg.norm(placed[:, 0]) @ _SPHERE_TURN
    matrix = np.eye(4)
    matrix[:3, :3], matrix[:3, 3] = float(sphere["radius"]) * turn, sphere["center"]
    return matrix


def world_map(origin: np.ndarray, along_u: np.ndarray, along_v: np.ndarray) -> SurfaceMap:
    """(u, v) -> origin + u along_u + v along_v, as a surface map into the world."""
    matrix = np.zeros((4, 3))
    matrix[:3, 0], matrix[:3, 1], matrix[:3, 2], matrix[3, 2] = along_u, along_v, origin, 1
    return matrix


def _rgb(out: object, name: str, colour: list) -> None:
    out.leaf("rgb", name=name, value=", ".join(repr(float(c)) for c in colour))


def _to_uv(out: object, rows: np.ndarray) -> None:
    """A to_uv transform from two affine rows over (u, v, 1), written as a 4 x 4 matrix: Mitsuba
    reads a 3 x 3 one as a linear map and drops its translation (measured: version 3.8.0)."""
    (a, b, c), (d, e, f) = rows
    values = [a, b, 0.0, c, d, e, 0.0, f, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0]
    out.open("transform", name="to_uv")
    out.leaf("matrix", value=" ".join(repr(float(v)) for v in values))
    out.close("transform")


def write_paint(
    out: object, name: str, paint: list | dict, uv_to_uv: SurfaceMap | None, uv_to_world: SurfaceMap | None
) -> None:
    """`name` (ka, kd, color0, color1) as an <rgb> or a <texture>. `uv_to_uv` maps Mitsuba's
    (u, v) to tracer's surface (u, v, 0); `uv_to_world` to the world point, where the shape is
    flat (a quad, a plane), else None (solid patterns are then refused)."""
    paint = folded(paint)
    if isinstance(paint, list):
        _rgb(out, name, paint)
        return
    kind, mapping = paint["pattern"], paint["mapping"]
    if "multiply" in paint:
        raise ToolError("an image times a colour: Mitsuba's bitmap has no factor")
    to_pattern = _affine4(paint["to_pattern"])
    if mapping == "uv" and uv_to_uv is not None:
        q = to_pattern @ uv_to_uv
    elif mapping == "solid" and kind == "checker" and uv_to_world is not None:
        q = to_pattern @ uv_to_world
    else:
        raise ToolError(f"a {kind} pattern in mapping {mapping} here: Mitsuba has no texture drawing it")
    if kind == "checker":
        _checkerboard(out, name, paint, q, uv_to_uv, uv_to_world)
    elif kind == "image":
        out.open("texture", type="bitmap", name=name)
        out.leaf("string", name="filename", value=paint["file"])
        out.leaf("string", name="filter_type", value="bilinear")
        out.leaf("string", name="wrap_mode", value=paint["wrap"])
        # Mitsuba's bitmap has (0, 0) at the top left: (x, 1 - y) of the pattern's point.
        _to_uv(out, np.array([q[0], -q[1] + np.array([0, 0, 1])]))
        out.close("texture")
    else:
        raise ToolError(f"a {kind} pattern: Mitsuba has no texture drawing it")


def _checkerboard(
    out: object, name: str, paint: dict, q: np.ndarray, uv_to_uv: SurfaceMap | None, uv_to_world: SurfaceMap | None
) -> None:
    """A checker whose point q (rows of x, y, z over (u, v, 1)) has one coordinate constant."""
    constant = [axis for axis in range(3) if abs(q[axis][0]) < 1e-12 and abs(q[axis][1]) < 1e-12]
    if not constant:
        raise ToolError("a checker whose cells vary along three axes across the surface: Mitsuba's is 2D")
    fixed = constant[0]
    varying = [axis for axis in range(3) if axis != fixed][:2]
    # Mitsuba's squares are half a unit over to_uv: halve tracer's nudged coordinates.
    rows = np.array([(q[axis] + np.array([0, 0, CHECKER_NUDGE])) / 2 for axis in varying])
    even_cells = np.floor(q[fixed][2] + CHECKER_NUDGE) % 2 == 0
    first, second = (paint["even"], paint["odd"]) if even_cells else (paint["odd"], paint["even"])
    out.open("texture", type="checkerboard", name=name)
    write_paint(out, "color0", first, uv_to_uv, uv_to_world)
    write_paint(out, "color1", second, uv_to_uv, uv_to_world)
    _to_uv(out, rows)
    out.close("texture")


def folded(paint: list | dict, factor: tuple = (1.0, 1.0, 1.0)) -> list | dict:
    """A colour or pattern with its `multiply` (and `factor`) folded into its colours: the same
    colours, written without `multiply`. An image keeps its `multiply` (its texels are a file)."""
    if isinstance(paint, list):
        return [c * f for c, f in zip(paint, factor, strict=True)]
    factor = tuple(f * m for f, m in zip(factor, paint.get("multiply", (1.0, 1.0, 1.0)), strict=True))
    out = {key: value for key, value in paint.items() if key != "multiply"}
    if paint["pattern"] == "image":
        if factor != (1.0, 1.0, 1.0):
            out["multiply"] = list(factor)
        return out
    if paint["pattern"] == "checker":
        out["even"], out["odd"] = folded(paint["even"], factor), folded(paint["odd"], factor)
    else:
        out["colors"] = [[at, folded(colour, factor)] for at, colour in paint["colors"]]
    return out


def patterned(material: dict) -> bool:
    return isinstance(material["ka"], dict) or isinstance(material["kd"], dict)
