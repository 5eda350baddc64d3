"""Geometry for NFF import: polygons into triangles (Mapbox Earcut), cones into unit meshes."""

from __future__ import annotations

import math
from collections.abc import Sequence

import mapbox_earcut
import numpy as np

LEAST_SIDES = 12  # the coarsest cone, however small or far


def polygon_normal(points: Sequence[Sequence[float]]) -> np.ndarray | None:
    """The unit normal of a planar polygon by Newell's method (counter-clockwise: towards the viewer), or None."""
    p = np.asarray(points, dtype=np.float64)
    q = np.roll(p, -1, axis=0)
    normal = np.array(
        [
            np.sum((p[:, 1] - q[:, 1]) * (p[:, 2] + q[:, 2])),
            np.sum((p[:, 2] - q[:, 2]) * (p[:, 0] + q[:, 0])),
            np.sum((p[:, 0] - q[:, 0]) * (p[:, 1] + q[:, 1])),
        ]
    )
    length = np.linalg.norm(normal)
    scale = np.max(np.abs(p - p[0])) if len(p) else 0.0
    if not length > 1e-12 * scale * scale:
        return None
    return normal / length


def triangulate(points: Sequence[Sequence[float]], normal: np.ndarray) -> np.ndarray:
    """Triangles (index triples into points) covering the planar polygon, each wound like the polygon.

    The polygon is projected onto the coordinate plane its normal is closest to and triangulated
    by Earcut, which takes non-convex polygons; fewer than n - 2 triangles means the outline
    crosses itself (the caller warns)."""
    p = np.asarray(points, dtype=np.float64)
    if len(p) == 3:
        return np.array([[0, 1, 2]], dtype=np.int64)
    drop = int(np.argmax(np.abs(normal)))
    keep = [axis for axis in range(3) if axis != drop]
    flat = np.ascontiguousarray(p[:, keep])
    indices = mapbox_earcut.triangulate_float64(flat, np.array([len(p)], dtype=np.uint32))
    triangles = indices.astype(np.int64).reshape(-1, 3)
    # Earcut's winding is its own: turn each triangle to face along the polygon's normal.
    a, b, c = p[triangles[:, 0]], p[triangles[:, 1]], p[triangles[:, 2]]
    backwards = np.einsum("ij,j->i", np.cross(b - a, c - a), normal) < 0
    triangles[backwards] = triangles[backwards][:, [0, 2, 1]]
    return triangles


def segments_for_error(
    radius: float, depth: float, pixels_per_unit_depth: float, max_error_pixels: float, most: int = 4096
) -> int:
    """Fewest sides of a polygon whose outline stays within max_error_pixels of a circle of
    `radius` seen at view depth `depth` (pixels_per_unit_depth: pixels per world unit at depth 1).

    The polygon's corners sit outside the circle and its edge midpoints inside, by the same
    amount r * (1 - cos(pi / n)) / (1 + cos(pi / n)) = r * tan^2(pi / 2n)."""
    allowed = max_error_pixels * depth / pixels_per_unit_depth  # in world units
    if allowed >= radius:
        return LEAST_SIDES
    sides = math.ceil(math.pi / (2 * math.atan(math.sqrt(allowed / radius))))
    return max(LEAST_SIDES, min(most, sides))


def frustum_arrays(apex_ratio: float, sides: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """An open cone frustum along +z, radius 1 at z = 0 and apex_ratio at z = 1, as (vertices,
    normals, faces): faces are rows (v0, n0, v1, n1, v2, n2) of 0-based indices.

    Corners lie at radius 2r / (1 + cos(pi / n)), so the facets straddle the true surface by
    r tan^2(pi / 2n) either way (segments_for_error); vertex normals are the true surface's."""
    angles = 2 * math.pi * np.arange(sides) / sides
    widen = 2 / (1 + math.cos(math.pi / sides))
    slope = 1 - apex_ratio  # radius falls by this much per unit of z
    rings = [
        np.column_stack([widen * radius * np.cos(angles), widen * radius * np.sin(angles), np.full(sides, z)])
        for z, radius in ((0.0, 1.0), (1.0, apex_ratio))
    ]
    vertices = np.vstack(rings)
    normals = np.column_stack([np.cos(angles), np.sin(angles), np.full(sides, slope)]) / math.hypot(1, slope)
    i = np.arange(sides)
    j = (i + 1) % sides
    b0, b1, t0, t1 = i, j, sides + i, sides + j
    if apex_ratio > 0:
        faces = np.vstack([np.column_stack([b0, i, b1, j, t1, j]), np.column_stack([b0, i, t1, j, t0, i])])
    else:  # a point at the apex: one triangle per side
        faces = np.column_stack([b0, i, b1, j, t0, i])
    return vertices, normals, faces


def frustum_mesh(apex_ratio: float, sides: int) -> str:
    """OBJ text of the unit frustum of frustum_arrays."""
    vertices, normals, faces = frustum_arrays(apex_ratio, sides)
    header = f"# open cone frustum: radius 1 at z = 0, {apex_ratio:.9g} at z = 1, {sides} sides"
    return header + "\n" + obj_text(vertices, normals, faces)


def obj_text(
    vertices: np.ndarray, normals: np.ndarray, faces: np.ndarray, first_vertex: int = 0, first_normal: int = 0
) -> str:
    """OBJ lines (v, vn, f v//vn) of triangles; indices in faces are 0-based within these arrays,
    written after first_vertex vertices and first_normal normals already in the file."""
    lines = [f"v {x:.9g} {y:.9g} {z:.9g}" for x, y, z in vertices + 0.0]  # + 0.0: no "-0"
    lines += [f"vn {x:.9g} {y:.9g} {z:.9g}" for x, y, z in normals + 0.0]
    offsets = np.array([first_vertex, first_normal] * 3) + 1
    lines += ["f {}//{} {}//{} {}//{}".format(*row) for row in (faces + offsets).tolist()]
    return "\n".join(lines) + "\n"


def rotation_matrix(axis: Sequence[float], angle_degrees: float) -> np.ndarray:
    """The rotation by angle_degrees about the unit axis (counter-clockwise looking down it)."""
    k = np.asarray(axis, dtype=np.float64)
    theta = math.radians(angle_degrees)
    cross = np.array([[0, -k[2], k[1]], [k[2], 0, -k[0]], [-k[1], k[0], 0]])
    return np.eye(3) + math.sin(theta) * cross + (1 - math.cos(theta)) * cross @ cross


def placed(
    vertices: np.ndarray,
    normals: np.ndarray,
    scale: Sequence[float],
    axis: Sequence[float],
    angle_degrees: float,
    translate: Sequence[float],
) -> tuple[np.ndarray, np.ndarray]:
    """Vertices and normals scaled, rotated and translated (tracer's order for a mesh block)."""
    rotation = rotation_matrix(axis, angle_degrees)
    scale = np.asarray(scale, dtype=np.float64)
    moved = (vertices * scale) @ rotation.T + np.asarray(translate, dtype=np.float64)
    turned = (normals / scale) @ rotation.T
    return moved, turned / np.linalg.norm(turned, axis=1, keepdims=True)


def frame_to_axis(direction: np.ndarray) -> tuple[tuple[float, float, float], float]:
    """(axis, angle in degrees) of the rotation that takes +z to the unit `direction`."""
    z = np.array([0.0, 0.0, 1.0])
    d = np.asarray(direction, dtype=np.float64)
    d = d / np.linalg.norm(d)
    cos_angle = float(np.clip(d[2], -1.0, 1.0))
    axis = np.cross(z, d)
    length = np.linalg.norm(axis)
    if length < 1e-15:
        return (1.0, 0.0, 0.0), (0.0 if cos_angle > 0 else 180.0)
    return tuple(axis / length), math.degrees(math.atan2(length, cos_angle))
