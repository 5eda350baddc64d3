"""The triangle meshes of a scene description in float64, as tracer has them, for the Mitsuba
integrator's float64 mirror chains (xcheck.plugins): Mitsuba keeps a mesh's placed corners and
normals in float32, and a mirror chain that bounces off a tessellated cylinder (SPD's rings)
would carry that rounding from bounce to bounce.

Every OBJ shape of the converted scene (mesh blocks, the planes' squares, the flat triangles) is
listed by its Mitsuba id with the triangles in Mitsuba's order (each face of the file in turn,
a polygon cut into a fan as Mitsuba's OBJ loader cuts it). As in tracer (src/accel/world.cpp,
src/accel/mesh_accel.cpp), a file that one block uses is placed: corners and normals in world
coordinates; a file that blocks share is kept in its own coordinates, with each block's map.
Normals: the file's when every face corner names one, else area-weighted over the corners as
placed (conventions.md); none (zero) under `shading flat` and for the flat shapes.
"""

from __future__ import annotations

import math
import pathlib
from collections.abc import Sequence

import numpy as np


class ObjUnreadable(Exception):
    """A file this reader does not take (tracer's own reader reports the problem itself)."""


def read_obj(path: str | pathlib.Path) -> tuple[np.ndarray, np.ndarray, list, np.ndarray]:
    """(positions (n, 3), normals (m, 3), faces, texture coordinates (k, 2)): each face a list of
    (position index, normal index or -1, texture coordinate index or -1) from 0, as the file
    gives them (negative indices counted from the end)."""
    positions, normals, faces, texcoords = [], [], [], []

    def index(parts: list, at: int, count: int) -> int:
        if len(parts) <= at or not parts[at]:
            return -1
        number = int(parts[at])
        return number - 1 if number > 0 else count + number

    with open(path, encoding="utf-8", errors="replace") as file:
        for line in file:
            fields = line.split("#", 1)[0].split()
            if not fields:
                continue
            if fields[0] == "v":
                positions.append([float(x) for x in fields[1:4]])
            elif fields[0] == "vn":
                normals.append([float(x) for x in fields[1:4]])
            elif fields[0] == "vt":
                texcoords.append([float(x) for x in (fields[1:3] + ["0"])[:2]])
            elif fields[0] == "f":
                face = []
                for corner in fields[1:]:
                    parts = corner.split("/")
                    face.append(
                        (
                            index(parts, 0, len(positions)),
                            index(parts, 2, len(normals)),
                            index(parts, 1, len(texcoords)),
                        )
                    )
                faces.append(face)
    return (
        np.array(positions, dtype=np.float64).reshape(-1, 3),
        np.array(normals, dtype=np.float64).reshape(-1, 3),
        faces,
        np.array(texcoords, dtype=np.float64).reshape(-1, 2),
    )


def fan_triangles(faces: list) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Each face cut into a fan from its first corner: (corners (t, 3) position indices, normal
    indices (t, 3), texture coordinate indices (t, 3)), -1 where a corner names none."""
    triangles = [(face[0], face[k], face[k + 1]) for face in faces for k in range(1, len(face) - 1)]
    corners, normal_ids, texcoord_ids = (
        np.array([[c[part] for c in t] for t in triangles], dtype=np.int64).reshape(-1, 3) for part in range(3)
    )
    return corners, normal_ids, texcoord_ids


def corner_texcoords(texcoords: np.ndarray, texcoord_ids: np.ndarray) -> np.ndarray:
    """The (u, v) of each triangle's corners (t, 3, 2), as tracer reads them: the file's `vt`
    when every face corner names one, else (0, 0) everywhere (src/io/obj_mesh.cpp)."""
    if not texcoord_ids.size or texcoord_ids.min() < 0 or texcoord_ids.max() >= len(texcoords):
        return np.zeros((len(texcoord_ids), 3, 2))
    return texcoords[texcoord_ids]


def uses_file_normals(file_normals: np.ndarray, normal_ids: np.ndarray) -> bool:
    """tracer's rule (src/io/obj_mesh.cpp): a file's own vertex normals count when it has some
    and every face corner names one (v//vn or v/vt/vn); otherwise normals are area-weighted.
    (tracer decides after dropping zero-area faces; a zero-area face without normals is the one
    case where the two could disagree.)"""
    return bool(
        len(file_normals) and normal_ids.size and normal_ids.min() >= 0 and normal_ids.max() < len(file_normals)
    )


def obj_normals_used(path: str | pathlib.Path) -> bool:
    """uses_file_normals for an OBJ file (False for a file this reader does not take)."""
    try:
        _, file_normals, faces, _ = read_obj(path)
        return uses_file_normals(file_normals, fan_triangles(faces)[1])
    except (ValueError, IndexError):
        return False


def _rotation(axis: Sequence[float], degrees: float) -> np.ndarray:
    """The rotation matrix about `axis` by `degrees` (right-handed, as glm::rotate)."""
    a = np.array(axis, dtype=np.float64)
    a /= math.sqrt(a @ a)
    c, s = math.cos(math.radians(degrees)), math.sin(math.radians(degrees))
    cross = np.array([[0.0, -a[2], a[1]], [a[2], 0.0, -a[0]], [-a[1], a[0], 0.0]])
    return c * np.eye(3) + s * cross + (1.0 - c) * np.outer(a, a)


def placement(shape: dict) -> tuple[np.ndarray, np.ndarray]:
    """tracer's Placement (src/scene/placement.h): (linear 3 x 3, translation) of the shape's
    scale, rotate and translate keys, or of its transform's steps in order."""
    linear, translate = np.eye(3), np.zeros(3)
    steps = shape.get("transform") or [
        {"scale": shape.get("scale", [1, 1, 1])},
        {"rotate": shape.get("rotate", {"axis": [0, 1, 0], "angle": 0})},
        {"translate": shape.get("translate", [0, 0, 0])},
    ]
    for step in steps:
        if "scale" in step:
            linear, translate = np.diag(step["scale"]) @ linear, np.diag(step["scale"]) @ translate
        elif "rotate" in step and step["rotate"]["angle"] != 0:
            rotation = _rotation(step["rotate"]["axis"], step["rotate"]["angle"])
            linear, translate = rotation @ linear, rotation @ translate
        elif "translate" in step:
            translate = translate + np.array(step["translate"], dtype=np.float64)
    return linear, translate


def _unit_rows(vectors: np.ndarray) -> np.ndarray:
    lengths = np.linalg.norm(vectors, axis=-1, keepdims=True)
    return np.divide(vectors, lengths, out=np.zeros_like(vectors), where=lengths > 0)


def area_weighted_normals(positions: np.ndarray, faces: np.ndarray) -> np.ndarray:
    """Vertex normals: the sum of the adjacent faces' cross products (face normal times twice
    the area), normalised; conventions.md. Mitsuba's own are angle-weighted."""
    a, b, c = (positions[faces[:, k]] for k in range(3))
    face_normals = np.cross(b - a, c - a)
    sums = np.zeros_like(positions)
    for k in range(3):
        np.add.at(sums, faces[:, k], face_normals)
    return _unit_rows(sums)


def _triangles(
    path: str, linear: np.ndarray, translate: np.ndarray, smooth: bool
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(corners (t, 3, 3), normals (t, 3, 3), (u, v) (t, 3, 2)) of an OBJ file mapped by (linear,
    translate), the file read once."""
    positions, file_normals, faces, texcoords = read_obj(path)
    corners, normal_ids, texcoord_ids = fan_triangles(faces)
    if corners.size and (corners.min() < 0 or corners.max() >= len(positions)):
        raise ObjUnreadable(f"{path}: a face names a vertex the file lacks")
    placed = positions @ linear.T + translate
    triangles, uvs = placed[corners], corner_texcoords(texcoords, texcoord_ids)
    if not smooth:
        return triangles, np.zeros_like(triangles), uvs
    if uses_file_normals(file_normals, normal_ids):
        normal_map = np.linalg.inv(linear).T
        return triangles, _unit_rows(file_normals @ normal_map.T)[normal_ids], uvs
    return triangles, area_weighted_normals(placed, corners)[corners], uvs


def exact_meshes(scene: dict, folder: pathlib.Path) -> tuple[list[str], list[np.ndarray], list[np.ndarray]]:
    """{Mitsuba shape id: (first triangle, triangle count, to_object 3 x 3, translation)} and the
    triangle table (corners (T, 3, 3), normals (T, 3, 3)) of the scene description `scene` as
    converted into `folder` (xcheck.convert.write_mitsuba_scene). A shape whose file this
    reader does not take is left out (its hits keep Mitsuba's float32 rounding)."""
    folder = pathlib.Path(folder)
    meshes = scene["meshes"]
    # (path, smooth, linear, translation) by shape id; shared files in their own coordinates.
    uses = {}
    for mesh in meshes:
        key = str(pathlib.Path(mesh["file"]).resolve())
        uses[key] = uses.get(key, 0) + 1
    sources = {}
    for index, mesh in enumerate(meshes):
        key = str(pathlib.Path(mesh["file"]).resolve())
        sources[f"mesh{index}"] = (key, mesh.get("shading") != "flat", *placement(mesh), uses[key] > 1)
    for index in range(len(scene["planes"])):
        sources[f"plane{index}"] = (str(folder / f"plane{index}.obj"), False, np.eye(3), np.zeros(3), False)
    for index, triangle in enumerate(scene.get("triangles", [])):
        sources[f"triangle{index}"] = (str(folder / f"triangle{index}.obj"), False, *placement(triangle), False)

    shapes, corner_parts, normal_parts, first, shared = {}, [], [], 0, {}
    for name, (path, smooth, linear, translate, instanced) in sources.items():
        try:
            if instanced:  # built once in the file's own coordinates; rays carried there
                if (path, smooth) not in shared:
                    triangles, normals, _ = _triangles(path, np.eye(3), np.zeros(3), smooth)
                    shared[(path, smooth)] = (first, len(triangles))
                    corner_parts.append(triangles)
                    normal_parts.append(normals)
                    first += len(triangles)
                start, count = shared[(path, smooth)]
                shapes[name] = (start, count, np.linalg.inv(linear), translate)
            else:
                triangles, normals, _ = _triangles(path, linear, translate, smooth)
                shapes[name] = (first, len(triangles), np.eye(3), np.zeros(3))
                corner_parts.append(triangles)
                normal_parts.append(normals)
                first += len(triangles)
        except (OSError, ValueError, IndexError, ObjUnreadable):
            continue
    empty = np.zeros((0, 3, 3))
    corners = np.concatenate(corner_parts) if corner_parts else empty
    normals = np.concatenate(normal_parts) if normal_parts else empty
    return shapes, corners, normals
