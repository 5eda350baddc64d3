"""NFF scene (nff.reader.Scene) to tracer's language: the .scn text and the OBJ files it names.

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
- cones and cylinders: one unit frustum OBJ per apex/base radius ratio, placed by scale, rotate
  and translate (instances), with enough sides that the outline is within `max_error_pixels`
  of the true cone for every cone in front of the eye.
"""

import dataclasses
import math

import numpy as np

from . import geometry


@dataclasses.dataclass
class Converted:
    scn: str
    meshes: dict  # file name (inside the meshes folder) -> OBJ text
    summary: dict


def _num(value):
    text = f"{float(value):.9g}"
    return "0" if text == "-0" else text


def _vec(values):
    return "(" + ", ".join(_num(v) for v in values) + ")"


def _colour(values):
    return _num(values[0]) if values[0] == values[1] == values[2] else _vec(values)


def _scale(values, factor):
    return tuple(factor * v for v in values)


class _Camera:
    """The tracer camera of an NFF view, and what a length at some depth measures in pixels."""

    def __init__(self, view, corner_rays):
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


def _material_text(name, fill, ambient):
    kd = _scale(fill.color, fill.kd)
    keys = [f"ka {_colour(_scale(kd, ambient))}", f"kd {_colour(kd)}"]
    if fill.ks > 0:
        keys += [f"ks {_num(fill.ks)}", f"n {_num(fill.shine)}", f"km {_num(fill.ks)}"]
    if fill.t > 0:
        keys += [f"kt {_num(fill.t)}", f"ior {_num(fill.ior)}"]
    return f"material {name} {{ {'  '.join(keys)} }}"


class _Writer:
    def __init__(self, scene, meshes_folder, corner_rays, max_error_pixels):
        self.scene = scene
        self.folder = meshes_folder
        self.camera = _Camera(scene.view, corner_rays)
        self.max_error_pixels = max_error_pixels
        self.warnings = []
        self.materials = {}  # Fill values -> (name, Fill)
        self.meshes = {}

    def material(self, fill):
        key = dataclasses.astuple(fill)
        if key not in self.materials:
            self.materials[key] = (f"m{len(self.materials)}", fill)
        return self.materials[key][0]

    def write(self):
        scene, camera = self.scene, self.camera
        lights = len(scene.lights)
        intensity = math.sqrt(max(lights, 1)) / (2 * max(lights, 1))
        shapes = self.sphere_lines() + self.polygon_lines() + self.cone_lines()
        lines = [
            f"# Converted from {scene.path} by tools/nff2scn (rules: tools/nff/convert.py, docs/spd.md).",
            f"# {len(scene.spheres)} spheres, {len(scene.polygons)} polygons, {len(scene.cones)} cones, "
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
            lines.append(f"light {{ position {_vec(light.position)}  color {_colour(color)} }}")
        lines.append("")
        for name, fill in self.materials.values():
            lines.append(_material_text(name, fill, intensity))
        lines.append("")
        lines += shapes
        summary = {
            "spheres": len(scene.spheres),
            "polygons": len(scene.polygons),
            "triangles": self.triangle_count,
            "cones": len(scene.cones),
            "cone_sides": self.cone_sides,
            "lights": lights,
            "materials": len(self.materials),
        }
        return Converted("\n".join(lines) + "\n", self.meshes, summary)

    def sphere_lines(self):
        return [
            f"sphere {{ center {_vec(s.center)}  radius {_num(s.radius)}  material {self.material(s.fill)} }}"
            for s in self.scene.spheres
        ]

    def polygon_lines(self):
        """One OBJ per material holding its polygons, triangulated; one mesh block each."""
        by_material = {}
        self.triangle_count = 0
        for polygon in self.scene.polygons:
            normal = geometry.polygon_normal(polygon.points)
            if normal is None:
                self.warnings.append((polygon.word, "a polygon without area (its corners are in a line): left out"))
                continue
            triangles = geometry.triangulate(polygon.points, normal)
            if len(triangles) < len(polygon.points) - 2:
                self.warnings.append((polygon.word, "a polygon whose outline crosses itself: partly left out"))
            by_material.setdefault(self.material(polygon.fill), []).append((polygon, normal, triangles))
            self.triangle_count += len(triangles)
        lines = []
        for name, polygons in by_material.items():
            file = f"polygons-{name}.obj"
            self.meshes[file] = _polygons_obj(polygons)
            lines.append(f'mesh {{ file "{self.folder}/{file}"  material {name} }}')
        return lines

    def cone_lines(self):
        """Each cone an instance of the unit frustum of its radius ratio, with sides enough for all."""
        placed, sides = [], {}
        for cone in self.scene.cones:
            base, apex = np.array(cone.base, dtype=np.float64), np.array(cone.apex, dtype=np.float64)
            r_base, r_apex = cone.base_radius, cone.apex_radius
            if r_apex > r_base:  # the unit frustum narrows towards +z
                base, apex, r_base, r_apex = apex, base, r_apex, r_base
            ratio = float(_num(r_apex / r_base))
            needed = self.sides_for(base, apex, r_base)
            sides[ratio] = max(sides.get(ratio, geometry.LEAST_SIDES), needed)
            placed.append((cone, base, apex, r_base, ratio))
        self.cone_sides = {ratio: count for ratio, count in sorted(sides.items())}
        lines = []
        for cone, base, apex, r_base, ratio in placed:
            file = f"cone-{_num(ratio)}-{sides[ratio]}.obj"
            if file not in self.meshes:
                self.meshes[file] = geometry.frustum_mesh(ratio, sides[ratio])
            axis = apex - base
            length = float(np.linalg.norm(axis))
            rotation_axis, angle = geometry.frame_to_axis(axis / length)
            lines.append(
                f'mesh {{ file "{self.folder}/{file}"  scale {_vec((r_base, r_base, length))}  '
                f"rotate {{ axis {_vec(rotation_axis)} angle {_num(angle)} }}  translate {_vec(base)}  "
                f"material {self.material(cone.fill)} }}"
            )
        return lines

    def sides_for(self, base, apex, radius):
        """Sides a cone needs for its outline to be within the error bound where the eye sees it."""
        camera = self.camera
        depths = [float(np.dot(point - camera.eye, camera.forward)) for point in (base, apex)]
        if max(depths) + radius < camera.hither:
            return geometry.LEAST_SIDES  # wholly behind the eye: not in view (its reflections are not measured)
        depth = max(min(depths) - radius, camera.hither)
        return geometry.segments_for_error(radius, depth, camera.pixels_per_unit_depth, self.max_error_pixels)


def _polygons_obj(polygons):
    """OBJ text of polygons: each its own corners, its normals (one flat, or the patch's), its triangles."""
    lines = []
    vertices = normals = 0
    for polygon, normal, triangles in polygons:
        for point in polygon.points:
            lines.append("v " + " ".join(_num(c) for c in point))
        if polygon.normals is None:
            lines.append("vn " + " ".join(_num(c) for c in normal))
            corner_normals = [normals + 1] * len(polygon.points)
            normals += 1
        else:
            for corner in polygon.normals:
                given = np.array(corner, dtype=np.float64)
                length = np.linalg.norm(given)
                lines.append("vn " + " ".join(_num(c) for c in (given / length if length > 0 else normal)))
            corner_normals = [normals + 1 + i for i in range(len(polygon.points))]
            normals += len(polygon.points)
        for triangle in triangles:
            lines.append("f " + " ".join(f"{vertices + 1 + i}//{corner_normals[i]}" for i in triangle))
        vertices += len(polygon.points)
    return "\n".join(lines) + "\n"


def convert(scene, meshes_folder, corner_rays=False, max_error_pixels=0.1):
    """Converted(scn, meshes, summary) for a Scene; meshes_folder is how the .scn names the OBJ folder."""
    writer = _Writer(scene, meshes_folder, corner_rays, max_error_pixels)
    converted = writer.write()
    converted.summary["warnings"] = writer.warnings
    return converted
