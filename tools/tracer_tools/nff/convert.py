"""NFF to tracer's language, streamed: shapes are written as the reader meets them, so memory
holds the materials and a bounded buffer, not the scene. The output is a .scn and the OBJ files
it names, written into a staging folder that nff2scn publishes only when all went well.

The rules, each a choice NFF leaves open (docs/spd.md gives the reasons):
- camera: NFF's angle spans the centres of the outer pixel rows; tracer's fovy spans the image
  edges, so fovy = 2 atan(tan(angle / 2) * N / (N - 1)) for N rows. `corner_rays` instead
  renders N + 1 rows whose centres are the corners of the N x N pixels (upstream's procedure:
  averaging each 2 x 2 block gives the N x N image).
- lights and ambient: intensity sqrt(L) / (2L) each for L lights (upstream's suggestion), times
  the light's colour when given; ambient ka = that intensity * Kd * colour.
- `f r g b Kd Ks Shine T ior`: kd = Kd * colour, ks = km = Ks (white highlight, mirror weight),
  n = Shine, kt = T, ior (1 when T is 0).
- ray tree depth 5 counting the eye ray: max_depth 4.
- polygons and patches: triangulated by Earcut into one OBJ per material, each polygon with its
  own corners and flat normal (patches keep their corner normals), wound like the polygon.
- cones and cylinders: tracer's own open cones (`cone { ... caps false }`: NFF's cones have no
  end caps), base to apex. With `cones="mesh"` (for measuring the analytic cone against it)
  instead one unit frustum OBJ per apex/base radius ratio, placed by scale, rotate and translate
  (instances), with enough sides that the outline is within `max_error_pixels` of the true cone
  for every cone in front of the eye; past MAX_CONE_MESHES different ratios, a cone is
  tessellated in place into its material's OBJ.
"""

from __future__ import annotations

import dataclasses
import math
import pathlib
import shutil
from collections.abc import Sequence

import numpy as np

from . import geometry
from .reader import Cone, Fill, Polygon, Scene, Sphere, TooManyMaterials, View, Word

MAX_MATERIALS = 65_536  # different `f` lines: each may become an OBJ file of its own
MAX_CONE_MESHES = 1_024  # different cone radius ratios given a unit mesh of their own
MAX_WARNINGS = 20  # shown; more are counted
BUFFERED_LINES = 200_000  # OBJ lines held before they are appended to their files


def _num(value: float) -> str:
    """The shortest text that reads back as the same double (no precision lost on the way)."""
    value = float(value)
    if value == int(value) and abs(value) < 1e15:
        return str(int(value))
    return repr(value)


def _vec(values: Sequence[float]) -> str:
    return "(" + ", ".join(_num(v) for v in values) + ")"


def _colour(values: Sequence[float]) -> str:
    return _num(values[0]) if values[0] == values[1] == values[2] else _vec(values)


def _scale(values: Sequence[float], factor: float) -> tuple[float, ...]:
    return tuple(factor * v for v in values)


class _Camera:
    """The tracer camera of an NFF view, and what a length at some depth measures in pixels."""

    def __init__(self, view: View, corner_rays: bool) -> None:
        width, height = view.resolution
        half = math.tan(math.radians(view.angle) / 2)
        rows = height + 1 if corner_rays else height
        self.width = width + 1 if corner_rays else width
        self.height = rows
        self.fovy = 2 * math.degrees(math.atan(half * rows / (height - 1)))
        self.eye = np.array(view.eye, dtype=np.float64)
        forward = np.array(view.lookat, dtype=np.float64) - self.eye
        self.forward = forward / np.linalg.norm(forward)
        tan_half = math.tan(math.radians(self.fovy) / 2)
        aspect = self.width / self.height
        # Pixels per world unit at depth 1, at the image corner where the projection stretches most.
        stretch = 1 + tan_half * tan_half * (1 + aspect * aspect)
        self.pixels_per_unit_depth = (self.height / 2) / tan_half * stretch
        self.hither = max(view.hither, 1e-6)


def _material_text(name: str, fill: Fill, ambient: float) -> str:
    kd = _scale(fill.color, fill.kd)
    keys = [f"ka {_colour(_scale(kd, ambient))}", f"kd {_colour(kd)}"]
    if fill.ks > 0:
        keys += [f"ks {_num(fill.ks)}", f"n {_num(fill.shine)}", f"km {_num(fill.ks)}"]
    if fill.t > 0:
        keys += [f"kt {_num(fill.t)}", f"ior {_num(fill.ior)}"]
    return f"material {name} {{ {'  '.join(keys)} }}"


@dataclasses.dataclass
class _ObjFile:
    """An OBJ file being appended to: counts so far, and lines not yet written."""

    vertices: int = 0
    normals: int = 0
    pending: list = dataclasses.field(default_factory=list)


class Writer:
    """The reader's shape sink: writes shape blocks to staging/shapes.part and triangles to
    staging/MESHES/*.obj as they come; finish() writes the .scn around them."""

    def __init__(
        self,
        staging: pathlib.Path,
        meshes_folder: str,
        corner_rays: bool = False,
        max_error_pixels: float = 0.1,
        cones: str = "analytic",
    ) -> None:
        self.staging = staging
        self.cones = cones
        self.folder = meshes_folder
        (staging / meshes_folder).mkdir()
        self.shapes = open(staging / "shapes.part", "w")  # noqa: SIM115  (closed by finish)
        self.corner_rays = corner_rays
        self.max_error_pixels = max_error_pixels
        self.camera = None
        self.materials = {}  # Fill values -> (name, Fill)
        self.objs = {}  # file name -> _ObjFile
        self.buffered = 0
        self.cone_sides = {}  # radius ratio -> most sides any of its cones needs
        self.warnings = []  # (word, message): the first MAX_WARNINGS
        self.more_warnings = 0
        self.counts = {"spheres": 0, "polygons": 0, "triangles": 0, "cones": 0}

    def material(self, fill: Fill, word: Word) -> str:
        key = dataclasses.astuple(fill)
        if key not in self.materials:
            if len(self.materials) >= MAX_MATERIALS:
                raise TooManyMaterials(word, f"more than {MAX_MATERIALS:,} different surfaces ('f' lines)")
            self.materials[key] = (f"m{len(self.materials)}", fill)
        return self.materials[key][0]

    def warn(self, word: Word, message: str) -> None:
        if len(self.warnings) < MAX_WARNINGS:
            self.warnings.append((word, message))
        else:
            self.more_warnings += 1

    # --- shapes, as the reader meets them ---------------------------------------------
    def sphere(self, scene: Scene, sphere: Sphere) -> None:
        name = self.material(sphere.fill, sphere.word)
        self.shapes.write(f"sphere {{ center {_vec(sphere.center)}  radius {_num(sphere.radius)}  material {name} }}\n")
        self.counts["spheres"] += 1

    def polygon(self, scene: Scene, polygon: Polygon) -> None:
        name = self.material(polygon.fill, polygon.word)
        normal = geometry.polygon_normal(polygon.points)
        if normal is None:
            self.warn(polygon.word, "a polygon without area (its corners are in a line): left out")
            return
        triangles = geometry.triangulate(polygon.points, normal)
        if len(triangles) < len(polygon.points) - 2:
            self.warn(polygon.word, "a polygon whose outline crosses itself: partly left out")
        points = np.asarray(polygon.points, dtype=np.float64)
        if polygon.normals is None:
            normals, corner_normal = normal[None, :], np.zeros(len(points), dtype=np.int64)
        else:
            given = np.asarray(polygon.normals, dtype=np.float64)
            length = np.linalg.norm(given, axis=1, keepdims=True)
            normals = np.where(length > 0, given / np.where(length > 0, length, 1), normal)
            corner_normal = np.arange(len(points))
        faces = np.column_stack(
            [
                triangles[:, 0],
                corner_normal[triangles[:, 0]],
                triangles[:, 1],
                corner_normal[triangles[:, 1]],
                triangles[:, 2],
                corner_normal[triangles[:, 2]],
            ]
        )
        self.append(f"polygons-{name}.obj", points, normals, faces)
        self.counts["polygons"] += 1
        self.counts["triangles"] += len(triangles)

    def cone(self, scene: Scene, cone: Cone) -> None:
        name = self.material(cone.fill, cone.word)
        self.counts["cones"] += 1
        if self.cones == "analytic":
            self.shapes.write(
                f"cone {{ base {_vec(cone.base)}  top {_vec(cone.apex)}  base_radius {_num(cone.base_radius)}  "
                f"top_radius {_num(cone.apex_radius)}  caps false  material {name} }}\n"
            )
            return
        if self.camera is None:
            self.camera = _Camera(scene.view, self.corner_rays)
        base, apex = np.array(cone.base, dtype=np.float64), np.array(cone.apex, dtype=np.float64)
        r_base, r_apex = cone.base_radius, cone.apex_radius
        if r_apex > r_base:  # the unit frustum narrows towards +z
            base, apex, r_base, r_apex = apex, base, r_apex, r_base
        ratio = float(_num(r_apex / r_base))
        axis = apex - base
        length = float(np.linalg.norm(axis))
        rotation_axis, angle = geometry.frame_to_axis(axis / length)
        sides = self.sides_for(base, apex, r_base)
        scale = (r_base, r_base, length)
        if ratio in self.cone_sides or len(self.cone_sides) < MAX_CONE_MESHES:
            self.cone_sides[ratio] = max(self.cone_sides.get(ratio, geometry.LEAST_SIDES), sides)
            self.shapes.write(
                f'mesh {{ file "{self.folder}/cone-{_num(ratio)}.obj"  scale {_vec(scale)}  '
                f"rotate {{ axis {_vec(rotation_axis)} angle {_num(angle)} }}  translate {_vec(base)}  "
                f"material {name} }}\n"
            )
            return
        vertices, normals, faces = geometry.frustum_arrays(ratio, sides)
        vertices, normals = geometry.placed(vertices, normals, scale, rotation_axis, angle, base)
        self.append(f"polygons-{name}.obj", vertices, normals, faces)

    def sides_for(self, base: np.ndarray, apex: np.ndarray, radius: float) -> int:
        """Sides a cone needs for its outline to be within the error bound where the eye sees it."""
        camera = self.camera
        depths = [float(np.dot(point - camera.eye, camera.forward)) for point in (base, apex)]
        if max(depths) + radius < camera.hither:
            return geometry.LEAST_SIDES  # wholly behind the eye: not in view (reflections are not measured)
        depth = max(min(depths) - radius, camera.hither)
        return geometry.segments_for_error(radius, depth, camera.pixels_per_unit_depth, self.max_error_pixels)

    # --- files -------------------------------------------------------------------------
    def append(self, file: str, vertices: np.ndarray, normals: np.ndarray, faces: np.ndarray) -> None:
        obj = self.objs.setdefault(file, _ObjFile())
        obj.pending.append(geometry.obj_text(vertices, normals, faces, obj.vertices, obj.normals))
        obj.vertices += len(vertices)
        obj.normals += len(normals)
        self.buffered += len(vertices) + len(normals) + len(faces)
        if self.buffered > BUFFERED_LINES:
            self.flush()

    def flush(self) -> None:
        for file, obj in self.objs.items():
            if obj.pending:
                with open(self.staging / self.folder / file, "a") as out:
                    out.writelines(obj.pending)
                obj.pending.clear()
        self.buffered = 0

    def finish(self, scene: Scene, scn_path: pathlib.Path) -> dict:
        """Writes the unit cone meshes and the .scn (header, then the shapes); the summary."""
        self.flush()
        self.shapes.close()
        for ratio, sides in self.cone_sides.items():
            (self.staging / self.folder / f"cone-{_num(ratio)}.obj").write_text(geometry.frustum_mesh(ratio, sides))
        camera = _Camera(scene.view, self.corner_rays)
        lights = len(scene.lights)
        intensity = math.sqrt(max(lights, 1)) / (2 * max(lights, 1))
        c = self.counts
        header = [
            f"# Converted from {scene.path} by tools/nff2scn (rules: tools/tracer_tools/nff/convert.py, docs/spd.md).",
            f"# {c['spheres']} spheres, {c['polygons']} polygons, {c['cones']} cones, "
            f"{lights} lights (intensity and ambient {intensity:.6g} each).",
            "",
            f"render {{ width {camera.width}  height {camera.height}  max_depth 4  "
            f"background {_colour(scene.background)} }}",
            f"camera {{ eye {_vec(scene.view.eye)}  lookat {_vec(scene.view.lookat)}  up {_vec(scene.view.up)}  "
            f"fovy {_num(camera.fovy)} }}",
            "",
        ]
        for light in scene.lights:
            color = _scale(light.color if light.color is not None else (1, 1, 1), intensity)
            header.append(f"light {{ position {_vec(light.position)}  color {_colour(color)} }}")
        header.append("")
        header += [_material_text(name, fill, intensity) for name, fill in self.materials.values()]
        header.append("")
        header += [
            f'mesh {{ file "{self.folder}/{file}"  material {file[len("polygons-") : -len(".obj")]} }}'
            for file in self.objs
        ]
        with open(scn_path, "w") as out:
            out.write("\n".join(header) + "\n")
            with open(self.staging / "shapes.part") as shapes:
                shutil.copyfileobj(shapes, out)
        (self.staging / "shapes.part").unlink()
        return {
            **c,
            "cone_sides": dict(sorted(self.cone_sides.items())),
            "lights": lights,
            "materials": len(self.materials),
        }

    def close(self) -> None:
        if not self.shapes.closed:
            self.shapes.close()
