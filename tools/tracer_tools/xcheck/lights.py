"""A scene's lights as the point lights they are made of (docs/guide/lights.md), for the
converters: a point light is itself; an area light is its samples1 x samples2 samples, spanning
its rectangle corner to corner, each with its share of the colour."""

from __future__ import annotations

import numpy as np


def light_points(light: dict) -> list[tuple[list[float], list[float]]]:
    """The light (an entry of `tracer --dump-json`'s lights) as (position, colour) point lights."""
    if "samples" not in light:
        return [(light["position"], light["color"])]
    n1, n2 = light["samples"]
    centre, edge1, edge2 = (np.array(light[k], dtype=np.float64) for k in ("position", "edge1", "edge2"))
    share = (np.array(light["color"], dtype=np.float64) * (1.0 / (n1 * n2))).tolist()
    points = []
    for i in range(n1):
        for j in range(n2):
            a = i / (n1 - 1) - 0.5 if n1 > 1 else 0.0
            b = j / (n2 - 1) - 0.5 if n2 > 1 else 0.0
            points.append(((centre + a * edge1 + b * edge2).tolist(), share))
    return points
