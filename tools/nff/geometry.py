"""Geometry for NFF import: polygons into triangles (Mapbox Earcut), cones into unit meshes."""

import math

import mapbox_earcut
import numpy as np

LEAST_SIDES = 12  # the coarsest cone, however small or far


def polygon_normal(points):
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


def triangulate(points, normal):
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


def segments_for_error(radius, depth, pixels_per_unit_depth, max_error_pixels, most=4096):
    """Fewest sides of a polygon whose outline stays within max_error_pixels of a circle of
    `radius` seen at view depth `depth` (pixels_per_unit_depth: pixels per world unit at depth 1).

    The polygon's corners sit outside the circle and its edge midpoints inside, by the same
    amount r * (1 - cos(pi / n)) / (1 + cos(pi / n)) = r * tan^2(pi / 2n)."""
    allowed = max_error_pixels * depth / pixels_per_unit_depth  # in world units
    if allowed >= radius:
        return LEAST_SIDES
    sides = math.ceil(math.pi / (2 * math.atan(math.sqrt(allowed / radius))))
    return max(LEAST_SIDES, min(most, sides))


def frustum_mesh(apex_ratio, sides):
    """OBJ text of an open cone frustum along +z: radius 1 at z = 0, apex_ratio at z = 1.

    Corners lie at radius r / cos^2(pi / 2n) ... precisely 2r / (1 + cos(pi / n)), so the facets
    straddle the true surface (segments_for_error); vertex normals are the true surface's."""
    angles = 2 * math.pi * np.arange(sides) / sides
    widen = 2 / (1 + math.cos(math.pi / sides))
    slope = 1 - apex_ratio  # radius falls by this much per unit of z
    lines = [f"# open cone frustum: radius 1 at z = 0, {apex_ratio:.9g} at z = 1, {sides} sides"]
    for z, radius in ((0.0, 1.0), (1.0, apex_ratio)):
        for angle in angles:
            lines.append(f"v {widen * radius * math.cos(angle):.9g} {widen * radius * math.sin(angle):.9g} {z:g}")
    norm = math.hypot(1, slope)
    for angle in angles:
        lines.append(f"vn {math.cos(angle) / norm:.9g} {math.sin(angle) / norm:.9g} {slope / norm:.9g}")
    for i in range(sides):
        j = (i + 1) % sides
        b0, b1, t0, t1 = i + 1, j + 1, sides + i + 1, sides + j + 1
        n0, n1 = i + 1, j + 1
        if apex_ratio > 0:
            lines.append(f"f {b0}//{n0} {b1}//{n1} {t1}//{n1}")
            lines.append(f"f {b0}//{n0} {t1}//{n1} {t0}//{n0}")
        else:  # a point at the apex: one triangle per side
            lines.append(f"f {b0}//{n0} {b1}//{n1} {t0}//{n0}")
    return "\n".join(lines) + "\n"


def frame_to_axis(direction):
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
