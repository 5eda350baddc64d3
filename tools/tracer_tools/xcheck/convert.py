"""Scene description (the JSON of `tracer --dump-json`) -> Mitsuba 3 XML.

The XML names the plugins of xcheck.plugins; a plain `mitsuba scene.xml` stops with Mitsuba's
error for an unknown plugin type. Planes become squares of half-size `plane_extent(...)`,
written as OBJ files beside the XML (write_mitsuba_scene).
"""

from __future__ import annotations

import math
import pathlib
from collections.abc import Sequence
from xml.sax.saxutils import quoteattr

import numpy as np

from . import PHONG_PLUGIN, WHITTED_PLUGIN, PeerCannotExpress, ToolError, exact_meshes, mitsuba_textures, round_shapes
from .lights import light_points, refuse_moving_samples

# Primary rays start this far in front of the eye (the camera's near clip). Secondary rays
# leave surfaces by Mitsuba's spawn_ray / spawn_ray_to, as tracer's by its spawn rule.
EPSILON = 1e-4

# The Whitted integrator unrolls its levels into one kernel: this many bounces at the most.
MAX_DEPTH = 64

# The strip of an infinite plane that its square leaves out is seen under less than
# 1/PLANE_MARGIN of a pixel (see plane_extent).
PLANE_MARGIN = 1000.0


def _numbers(values: Sequence[float]) -> str:
    return ", ".join(repr(float(v)) for v in values)


def _sub(a: Sequence[float], b: Sequence[float]) -> list[float]:
    return [x - y for x, y in zip(a, b, strict=False)]


def _dot(a: Sequence[float], b: Sequence[float]) -> float:
    return sum(x * y for x, y in zip(a, b, strict=False))


def _cross(a: Sequence[float], b: Sequence[float]) -> list[float]:
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def _normalize(a: Sequence[float]) -> list[float]:
    length = math.sqrt(_dot(a, a))
    return [x / length for x in a]


def pixel_angle(scene: dict) -> float:
    """Angle (radians) one pixel spans vertically at the image centre."""
    camera, render = scene["camera"], scene["render"]
    return 2 * math.tan(math.radians(camera["fovy"]) / 2) / render["height"]


def plane_extent(scene: dict, plane: dict) -> float:
    """Half-size of the square that stands in for an infinite plane.

    A ray from a point at height h over the plane that misses a square of half-size R
    centred under the eye meets the plane beyond R, i.e. less than about h/R radians above or
    below the horizon. With h the largest height of the eye or any sphere over the plane, and
    R = PLANE_MARGIN * h / (angle of one pixel), that strip is under 1/PLANE_MARGIN of a pixel
    for primary rays, and narrower still after convex (sphere) mirrors.
    """
    normal = _normalize(plane["normal"])
    height = abs(_dot(_sub(scene["camera"]["eye"], plane["point"]), normal))
    for sphere in scene["spheres"]:
        height = max(height, abs(_dot(_sub(sphere["center"], plane["point"]), normal)) + sphere["radius"])
    return PLANE_MARGIN * max(height, 1.0) / pixel_angle(scene)


def plane_frame(scene: dict, plane: dict) -> tuple[list[float], list[float], list[float]]:
    """The centre (the foot of the eye) and the two unit directions plane_mesh_obj lays its
    square along: a point of the plane is centre + a tangent + b bitangent, its OBJ's vt (a, b)."""
    normal = _normalize(plane["normal"])
    eye = scene["camera"]["eye"]
    height = _dot(_sub(eye, plane["point"]), normal)
    centre = _sub(eye, [x * height for x in normal])
    helper = [1.0, 0.0, 0.0] if abs(normal[0]) < 0.9 else [0.0, 1.0, 0.0]
    tangent = _normalize(_cross(helper, normal))
    return centre, tangent, _cross(normal, tangent)  # (tangent, bitangent, normal) is right-handed


def plane_mesh_obj(scene: dict, plane: dict) -> str:
    """OBJ text of a square of half-size plane_extent(...) in the plane, centred at the foot of
    the eye: a centre square of half-size h (as in plane_extent) and around it rings, each
    twice as wide as the one inside, so that every triangle is about as large as its distance
    from the centre. Mitsuba intersects triangles in float32 (Embree): one pair of triangles
    10^6 units wide loses hits near the eye."""
    normal = _normalize(plane["normal"])
    height = _dot(_sub(scene["camera"]["eye"], plane["point"]), normal)
    centre, tangent, bitangent = plane_frame(scene, plane)
    size, extent = max(abs(height), 1.0), plane_extent(scene, plane)
    lines = [
        f"# plane through {plane['point']} with normal {plane['normal']}: half-size {extent:.6g}",
        f"vn {normal[0]!r} {normal[1]!r} {normal[2]!r}",
    ]
    squares = 0
    while True:
        for a, b in ((-1, -1), (1, -1), (1, 1), (-1, 1)):  # counter-clockwise seen from the normal
            point = [c + size * (a * t + b * u) for c, t, u in zip(centre, tangent, bitangent, strict=False)]
            lines.append(f"v {point[0]!r} {point[1]!r} {point[2]!r}")
            lines.append(f"vt {size * a!r} {size * b!r}")  # for textures (xcheck.mitsuba_textures)
        squares += 1
        if size >= extent:
            break
        size = min(2 * size, extent)

    def face(*corners):
        return "f " + " ".join(f"{corner}/{corner}/1" for corner in corners)

    lines += [face(1, 2, 3), face(1, 3, 4)]
    for ring in range(1, squares):
        inner, outer = 4 * (ring - 1) + 1, 4 * ring + 1
        for side in range(4):
            nxt = (side + 1) % 4
            lines += [face(inner + side, outer + side, outer + nxt), face(inner + side, outer + nxt, inner + nxt)]
    return "\n".join(lines) + "\n"


class _Writer:
    def __init__(self) -> None:
        self.lines = []
        self.indent = 0

    def open(self, tag: str, **attributes: object) -> None:
        self.line(f"<{tag}{self._attributes(attributes)}>")
        self.indent += 1

    def close(self, tag: str) -> None:
        self.indent -= 1
        self.line(f"</{tag}>")

    def leaf(self, tag: str, **attributes: object) -> None:
        self.line(f"<{tag}{self._attributes(attributes)}/>")

    def line(self, text: str) -> None:
        self.lines.append("    " * self.indent + text)

    @staticmethod
    def _attributes(attributes: dict) -> str:
        return "".join(f" {name.rstrip('_')}={quoteattr(str(value))}" for name, value in attributes.items())


def _material_key(material: dict) -> tuple[str, str]:
    return (material["name"], repr(sorted(material.items())))


SHAPE_KINDS = ("spheres", "planes", "meshes", "triangles", "quads", "boxes", "cones", "discs")


def shapes(scene: dict) -> list[dict]:
    """Every shape of the scene description, of every kind (older dumps lack the flat shapes)."""
    return [shape for kind in SHAPE_KINDS for shape in scene.get(kind, [])]


def refracts(scene: dict) -> bool:
    """True if some shape's material transmits (kt > 0): the integrator then branches."""
    return any(any(shape["material"].get("kt", [0, 0, 0])) for shape in shapes(scene))


def _placement(out: _Writer, shape: dict, before: list | None = None) -> None:
    """The shape's to_world: an optional matrix of its own (rows), then tracer's placement:
    scale, rotate about the axis, translate, or its transform steps in order (Mitsuba applies a
    transform's children in the order written)."""
    out.open("transform", name="to_world")
    if before is not None:
        out.leaf("matrix", value=" ".join(repr(float(x)) for row in before for x in row))
    steps = shape.get("transform") or [
        {"scale": shape["scale"]},
        {"rotate": shape["rotate"]},
        {"translate": shape["translate"]},
    ]
    for step in steps:
        if "scale" in step:
            out.leaf("scale", value=_numbers(step["scale"]))
        elif "rotate" in step and step["rotate"]["angle"] != 0:
            out.leaf("rotate", value=_numbers(step["rotate"]["axis"]), angle=repr(float(step["rotate"]["angle"])))
        elif "translate" in step:
            out.leaf("translate", value=_numbers(step["translate"]))
    out.close("transform")


def mirrors(shape: dict) -> bool:
    """True if the shape's placement turns space inside out (an odd number of negative scale
    factors). tracer keeps such a shape's normals pointing outwards; Mitsuba takes its face
    normals from the placed winding, which a mirror reverses, so the converter flips them back."""
    steps = shape.get("transform") or [{"scale": shape["scale"]}]
    negative = sum(x < 0 for step in steps if "scale" in step for x in step["scale"])
    return negative % 2 == 1


def _affine(columns: Sequence[Sequence[float]], origin: Sequence[float]) -> list[list[float]]:
    """A 4 x 4 matrix (rows) mapping the unit axes to `columns` and the origin to `origin`."""
    return [[*(column[row] for column in columns), origin[row]] for row in range(3)] + [[0.0, 0.0, 0.0, 1.0]]


def quad_to_rectangle(quad: dict) -> list[list[float]]:
    """The matrix taking Mitsuba's rectangle ([-1, 1]^2 at z = 0, normal +z) onto the quad:
    half edges as x and y, the unit normal edge1 x edge2 as z, the quad's centre as origin."""
    edge1, edge2 = quad["edge1"], quad["edge2"]
    centre = [c + 0.5 * (a + b) for c, a, b in zip(quad["corner"], edge1, edge2, strict=True)]
    half1, half2 = [0.5 * x for x in edge1], [0.5 * x for x in edge2]
    return _affine([half1, half2, _normalize(_cross(edge1, edge2))], centre)


def box_to_cube(box: dict) -> list[list[float]]:
    """The matrix taking Mitsuba's cube ([-1, 1]^3) onto the box before placing."""
    low, high = box["min"], box["max"]
    half = [0.5 * (b - a) for a, b in zip(low, high, strict=True)]
    return _affine(
        [[half[0], 0, 0], [0, half[1], 0], [0, 0, half[2]]], [0.5 * (a + b) for a, b in zip(low, high, strict=True)]
    )


def triangle_obj(triangle: dict) -> str:
    """OBJ text of a flat triangle."""
    corners = "".join(f"v {p[0]!r} {p[1]!r} {p[2]!r}\n" for p in (triangle["a"], triangle["b"], triangle["c"]))
    return corners + "vt 0 0\nvt 1 0\nvt 0 1\nf 1/1 2/2 3/3\n"  # (u, v) as tracer's


def _write_bsdf(out: _Writer, material: dict, bsdf_id: str | None = None, maps: tuple = (None, None)) -> None:
    """A material as the Phong plugin; a patterned ka or kd as a texture over the shape's (u, v),
    `maps` being the shape's (uv_to_uv, uv_to_world) (xcheck.mitsuba_textures)."""
    out.open("bsdf", type=PHONG_PLUGIN, **({"id": bsdf_id} if bsdf_id else {}))
    for name in ("ka", "kd"):
        mitsuba_textures.write_paint(out, name, material.get(name, [0, 0, 0]), *maps)
    for name in ("ks", "km", "kt"):
        out.leaf("rgb", name=name, value=_numbers(material.get(name, [0, 0, 0])))
    out.leaf("float", name="n", value=repr(float(material["n"])))
    out.leaf("float", name="ior", value=repr(float(material.get("ior", 1.0))))
    out.close("bsdf")


def _use_material(out: _Writer, ids: dict, material: dict, maps: tuple = (None, None)) -> None:
    """A shape's material: a reference to the shared one, or, patterned, its own with textures
    placed on this shape."""
    if mitsuba_textures.patterned(material):
        _write_bsdf(out, material, maps=maps)
    else:
        out.leaf("ref", id=ids[_material_key(material)])


def _flat_maps(kind: str, shape: dict, scene: dict) -> tuple:
    """(uv_to_uv, uv_to_world) of a quad, a triangle or a plane as this converter writes them."""
    if kind == "plane":
        centre, tangent, bitangent = (np.array(v) for v in plane_frame(scene, shape))
        return None, mitsuba_textures.world_map(centre + bitangent, tangent, -bitangent)  # vt's v turned
    linear, translate = exact_meshes.placement(shape)
    if kind == "quad":
        corner, edge1, edge2 = (np.array(shape[k], dtype=np.float64) for k in ("corner", "edge1", "edge2"))
        world = mitsuba_textures.world_map(linear @ corner + translate, linear @ edge1, linear @ edge2)
        return mitsuba_textures.uv_map_of_rectangle(), world
    if kind == "triangle":
        a, b, c = (np.array(shape[k], dtype=np.float64) for k in ("a", "b", "c"))
        world = mitsuba_textures.world_map(linear @ c + translate, linear @ (b - a), -(linear @ (c - a)))
        return mitsuba_textures.uv_map_of_obj(), world
    return None, None


# The lights beyond points and their samples, as the converter names them when it skips a scene.
LIGHT_WORDS = {"spot": "a spotlight", "parallel": "a parallel light"}


def to_mitsuba_xml(scene: dict) -> str:
    """The Mitsuba 3 XML text for a scene description (a dict from `tracer --dump-json`)."""
    render, camera = scene["render"], scene["camera"]
    if render["max_depth"] > MAX_DEPTH:
        raise ToolError(
            f"max_depth {render['max_depth']}: the Mitsuba integrator unrolls one level per "
            f"bounce and takes at most {MAX_DEPTH}"
        )
    if scene.get("solids"):
        raise PeerCannotExpress(
            "the scene has solids (union, merge, intersection, difference), which Mitsuba 3 cannot express "
            "(it has no CSG); check this scene with tools/crosscheck --with povray"
        )
    beyond_points = sorted(
        {LIGHT_WORDS[light["kind"]] for light in scene["lights"] if "kind" in light}
        | {"fading" for light in scene["lights"] if "fade_distance" in light}
    )
    for light in scene["lights"]:
        refuse_moving_samples(light)
    if beyond_points:
        raise PeerCannotExpress(
            f"the scene has {' and '.join(beyond_points)}, which the Phong integrator's point emitters cannot "
            "express (Mitsuba's own lights are physically based); check this scene with tools/crosscheck --with povray"
        )
    if render.get("transparent_shadows") and refracts(scene):
        raise ToolError(
            "transparent_shadows: the Mitsuba integrator's shadows are opaque; check this scene with "
            "tools/crosscheck --with povray"
        )
    out = _Writer()
    out.line("<?xml version='1.0' encoding='utf-8'?>")
    out.line(
        f"<!-- From `tracer --dump-json {scene['source']}` by tools/tracer_tools/xcheck. It names the "
        f"plugins {WHITTED_PLUGIN} and {PHONG_PLUGIN}: render it with tools/crosscheck "
        "(or xcheck.mitsuba_render), which registers them. -->"
    )
    out.open("scene", version="3.0.0")

    # Step 1: the Whitted integrator with the render settings.
    out.open("integrator", type=WHITTED_PLUGIN)
    out.leaf("integer", name="max_depth", value=render["max_depth"])
    out.leaf("boolean", name="shadows", value="true" if render["shadows"] else "false")
    out.leaf("rgb", name="background", value=_numbers(render["background"]))
    out.leaf("boolean", name="refracts", value="true" if refracts(scene) else "false")
    # The camera in double precision, for the integrator's float64 primary rays: eye, lookat,
    # up, fovy, width, height and the sample grid's side.
    grid = round(math.sqrt(render["samples"]))
    numbers = [
        *camera["eye"],
        *camera["lookat"],
        *camera["up"],
        camera["fovy"],
        render["width"],
        render["height"],
        grid,
    ]
    out.leaf("string", name="camera", value=" ".join(repr(float(x)) for x in numbers))
    # The spheres in double precision, for the integrator's float64 mirror chains (shape
    # "sphere<i>" is entry i): Mitsuba's own sphere keeps its centre and radius in float32.
    if scene["spheres"]:
        numbers = (repr(float(x)) for sphere in scene["spheres"] for x in [*sphere["center"], sphere["radius"]])
        out.leaf("string", name="spheres", value=" ".join(numbers))
    out.close("integrator")

    # Step 2: the camera: vertical field of view; pixel centres (or the centres of an N x N
    # grid of cells) through an unjittered stratified sampler; box filter; float RGB film.
    # The film renders rows crop_y .. crop_y + crop_height - 1 (all by default; big
    # supersampled images are rendered in strips: mitsuba_render.render_in_strips).
    out.leaf("default", name="crop_y", value=0)
    out.leaf("default", name="crop_height", value=render["height"])
    out.open("sensor", type="perspective")
    out.leaf("string", name="fov_axis", value="y")
    out.leaf("float", name="fov", value=repr(float(camera["fovy"])))
    out.leaf("float", name="near_clip", value=repr(EPSILON))
    out.leaf("float", name="far_clip", value="1e30")
    out.open("transform", name="to_world")
    out.leaf("lookat", origin=_numbers(camera["eye"]), target=_numbers(camera["lookat"]), up=_numbers(camera["up"]))
    out.close("transform")
    out.open("sampler", type="stratified")
    out.leaf("integer", name="sample_count", value=render["samples"])
    out.leaf("boolean", name="jitter", value="false")
    out.close("sampler")
    out.open("film", type="hdrfilm")
    out.leaf("integer", name="width", value=render["width"])
    out.leaf("integer", name="height", value=render["height"])
    out.leaf("integer", name="crop_offset_y", value="$crop_y")
    out.leaf("integer", name="crop_height", value="$crop_height")
    out.leaf("string", name="pixel_format", value="rgb")
    out.leaf("string", name="component_format", value="float32")
    out.leaf("rfilter", type="box")
    out.close("film")
    out.close("sensor")

    # Step 3: materials, each once.
    ids = {}
    for shape in shapes(scene):
        material = shape["material"]
        key = _material_key(material)
        if key in ids or mitsuba_textures.patterned(material):  # patterned: each shape its own
            continue
        ids[key] = f"material{len(ids)}-{material['name']}"
        _write_bsdf(out, material, ids[key])

    # Step 4: shapes.
    for index, sphere in enumerate(scene["spheres"]):
        out.open("shape", type="sphere", id=f"sphere{index}")
        if mitsuba_textures.patterned(sphere["material"]):  # turned to lay (u, v) as tracer does
            out.open("transform", name="to_world")
            out.leaf("matrix", value=" ".join(repr(float(v)) for v in mitsuba_textures.sphere_to_world(sphere).ravel()))
            out.close("transform")
        else:
            out.leaf("point", name="center", value=_numbers(sphere["center"]))
            out.leaf("float", name="radius", value=repr(float(sphere["radius"])))
        _use_material(out, ids, sphere["material"], (mitsuba_textures.uv_map_of_sphere(), None))
        out.close("shape")
    for index, plane in enumerate(scene["planes"]):
        out.line(
            f"<!-- plane {index}: a square of half-size {plane_extent(scene, plane):.6g} "
            "(xcheck.convert.plane_extent, plane_mesh_obj) -->"
        )
        out.open("shape", type="obj", id=f"plane{index}")
        out.leaf("string", name="filename", value=f"plane{index}.obj")
        _use_material(out, ids, plane["material"], _flat_maps("plane", plane, scene))
        out.close("shape")
    for index, mesh in enumerate(scene["meshes"]):
        out.open("shape", type="obj", id=f"mesh{index}")
        out.leaf("string", name="filename", value=mesh["file"])
        _placement(out, mesh)
        if mesh.get("shading") == "flat":  # tracer's `shading flat`: each triangle's own normal
            out.leaf("boolean", name="face_normals", value="true")
        if mirrors(mesh):
            out.leaf("boolean", name="flip_normals", value="true")
        _use_material(out, ids, mesh["material"], (mitsuba_textures.uv_map_of_obj(), None))
        out.close("shape")
    # The flat shapes: Mitsuba's own rectangle and cube (not tracer's triangles), and a one-face
    # OBJ for each triangle.
    flat = [("triangle", "obj", t, None) for t in scene.get("triangles", [])]
    flat += [("quad", "rectangle", q, quad_to_rectangle(q)) for q in scene.get("quads", [])]
    flat += [("box", "cube", b, box_to_cube(b)) for b in scene.get("boxes", [])]
    for index, (kind, plugin, shape, matrix) in enumerate(flat):
        out.open("shape", type=plugin, id=f"{kind}{index}")
        if kind == "triangle":
            out.leaf("string", name="filename", value=f"triangle{index}.obj")
            out.leaf("boolean", name="face_normals", value="true")
        _placement(out, shape, matrix)
        if mirrors(shape):
            out.leaf("boolean", name="flip_normals", value="true")
        _use_material(out, ids, shape["material"], _flat_maps(kind, shape, scene))
        out.close("shape")

    # The round shapes: cones and cylinders as OBJ files (round_shapes.cone_obj), discs and caps
    # as disks.
    for index, cone in enumerate(scene.get("cones", [])):
        out.open("shape", type="obj", id=f"cone{index}")
        out.leaf("string", name="filename", value=f"cone{index}.obj")
        _use_material(out, ids, cone["material"])
        out.close("shape")
    for name, matrix, material in round_shapes.disks_of(scene):
        out.open("shape", type="disk", id=name)
        out.open("transform", name="to_world")
        out.leaf("matrix", value=" ".join(repr(float(x)) for row in matrix for x in row))
        out.close("transform")
        _use_material(out, ids, material)
        out.close("shape")

    # Step 5: point lights (an area light's samples each one); the integrator undoes Mitsuba's
    # 1/r^2 fall-off.
    for light in scene["lights"]:
        for position, color in light_points(light):
            out.open("emitter", type="point")
            out.leaf("point", name="position", value=_numbers(position))
            out.leaf("rgb", name="intensity", value=_numbers(color))
            out.close("emitter")

    out.close("scene")
    return "\n".join(out.lines) + "\n"


def write_mitsuba_scene(scene: dict, folder: pathlib.Path) -> pathlib.Path:
    """Writes folder/scene.xml and the OBJ files of its planes, triangles and cones; returns the
    XML's path."""
    folder = pathlib.Path(folder)
    for index, plane in enumerate(scene["planes"]):
        (folder / f"plane{index}.obj").write_text(plane_mesh_obj(scene, plane))
    for index, triangle in enumerate(scene.get("triangles", [])):
        (folder / f"triangle{index}.obj").write_text(triangle_obj(triangle))
    for index, cone in enumerate(scene.get("cones", [])):
        sides = round_shapes.sides_for(cone, scene["camera"]["eye"], pixel_angle(scene))
        (folder / f"cone{index}.obj").write_text(round_shapes.cone_obj(cone, sides))
    xml_path = folder / "scene.xml"
    xml_path.write_text(to_mitsuba_xml(scene))
    return xml_path
